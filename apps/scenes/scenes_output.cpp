// What talus-scenes writes (scenes_output.h).
#include "scenes_output.h"

#include <cerrno>
#include <cstring>
#include <iostream>

#include "report_writer.h"
#include "talus/harness/scenes/bench_perturb.h"

namespace talus::scenes {

bool PrintLine(const std::string& line) {
  errno = 0;
  std::cout << line << '\n' << std::flush;
  if (std::cout) return true;
  std::cerr << "talus-scenes: stdout: cannot write (" << (errno != 0 ? std::strerror(errno) : "write failed")
            << ")\n";
  return false;
}

bool PrintReport(const harness::BenchReport& report, bool csv) {
  return PrintLine(csv ? FormatCsv(report) : FormatJson(report));
}

harness::BenchProgress SeriesProgress(const std::string& label) {
  return [label](int step, int steps) {
    if (step % 100 == 0 || step == steps) std::cerr << label << ": step " << step << "/" << steps << '\n';
  };
}

void PrintRepeatSummary(const std::vector<harness::BenchReport>& series) {
  auto summary = harness::SummarizeRepeats(series);
  if (summary) std::cerr << harness::FormatRepeatSummary(series.front(), summary.Value()) << '\n';
}

}  // namespace talus::scenes
