// Perturbed repeats of a reference scene (see talus/harness/scenes/bench_perturb.h).
#include "talus/harness/scenes/bench_perturb.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "talus/harness/support/number_text.h"

namespace talus::harness {

std::optional<std::string> BenchRepeatsProblem(int repeats) {
  if (repeats < 1 || repeats > kMaxBenchRepeats) {
    return "repeats " + std::to_string(repeats) + ": must be in [1, " + std::to_string(kMaxBenchRepeats) +
           "]";
  }
  return std::nullopt;
}

std::optional<double> BenchVerdictFigure(const BenchReport& report) {
  if (!report.skipped.empty()) return std::nullopt;
  return report.drift ? report.drift : report.maxPenetration;
}

std::optional<bool> BenchVerdict(const BenchReport& report) {
  if (!report.skipped.empty()) return std::nullopt;
  if (report.drift) return *report.drift <= kPyramidDriftGoal;  // false for NaN
  if (report.escaped) return *report.escaped == 0;
  return std::nullopt;
}

Result<BenchRepeatSummary> SummarizeRepeats(const std::vector<BenchReport>& repeats) {
  std::vector<double> figures;
  BenchRepeatSummary summary;
  bool anyNan = false;
  for (const BenchReport& report : repeats) {
    const std::optional<double> figure = BenchVerdictFigure(report);
    const std::optional<bool> verdict = BenchVerdict(report);
    if (!figure || !verdict) continue;
    anyNan = anyNan || std::isnan(*figure);
    figures.push_back(*figure);
    if (*verdict) ++summary.verdictsHeld;
  }
  if (figures.empty()) return Error{"no repeat was run (all skipped or empty), nothing to summarize"};
  summary.runs = static_cast<int>(figures.size());
  summary.sameVerdict = summary.verdictsHeld == 0 || summary.verdictsHeld == summary.runs;
  if (anyNan) {
    summary.min = summary.median = summary.max = std::nan("");
    return summary;
  }
  std::sort(figures.begin(), figures.end());
  const size_t n = figures.size();
  summary.min = figures.front();
  summary.max = figures.back();
  summary.median = n % 2 == 1 ? figures[n / 2] : 0.5 * (figures[n / 2 - 1] + figures[n / 2]);
  return summary;
}

std::string FormatRepeatSummary(const BenchReport& first, const BenchRepeatSummary& summary) {
  const bool pyramid = first.drift.has_value();
  std::ostringstream line;
  line << first.scene << " " << first.parameter << " " << first.engine << ": "
       << (pyramid ? "drift_m" : "max_penetration_m") << " over " << summary.runs << " repeats";
  if (first.perturbation) {
    line << " (+-" << FormatNumber(first.perturbation->amount) << " m, first seed "
         << first.perturbation->seed << ")";
  }
  line << ": min " << FormatNumber(summary.min) << " median " << FormatNumber(summary.median) << " max "
       << FormatNumber(summary.max) << "; verdict "
       << (pyramid ? "drift_m <= " + FormatNumber(kPyramidDriftGoal) : std::string("escaped == 0"))
       << " held in " << summary.verdictsHeld << " of " << summary.runs << ": "
       << (summary.sameVerdict ? "same in every repeat" : "DIFFERS between repeats");
  return line.str();
}

}  // namespace talus::harness
