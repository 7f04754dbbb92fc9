// CSV and JSON-lines formatting of benchmark reports (see report_writer.h).
#include "report_writer.h"

#include <cmath>
#include <string>
#include <vector>

#include "talus/harness/scenes/bench_report_json.h"
#include "talus/harness/support/number_text.h"

namespace talus::scenes {
namespace {

// Six significant digits: enough for milliseconds and millimetres, short
// enough to read in a terminal.
std::string Number(double value) {
  return std::isnan(value) ? std::string("nan") : harness::FormatNumber(value);
}

std::string Optional(const std::optional<double>& value) { return value ? Number(*value) : std::string(); }

// CSV quoting (RFC 4180): double quotes around, inner quotes doubled.
std::string Quote(const std::string& text) {
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

// "UpdateBroadPhase=0.12;FindContacts=3.4;...": each stage's mean ms in
// one field (stage names hold no ',' or ';'), so the columns stay fixed
// whatever stages an engine times.
std::string StageField(const std::vector<harness::BenchStage>& stages) {
  std::string field;
  for (const harness::BenchStage& stage : stages) {
    if (!field.empty()) field += ';';
    field += stage.name + "=" + Number(stage.msMean);
  }
  return field;
}

}  // namespace

std::string CsvHeader(bool perturbed) {
  std::string header =
      "engine,scene,parameter,bodies,threads,steps,iterations,substeps,total_ms,ms_per_step_mean,"
      "ms_per_step_max,max_contacts,drift_m,max_penetration_m,kinetic_energy_j,escaped,skipped,stage_ms_mean";
  if (perturbed) header.append(",repeat,perturb_m,perturb_seed");
  return header;
}

std::string FormatCsv(const harness::BenchReport& report) {
  std::string line = report.engine + "," + report.scene + "," + std::to_string(report.parameter) + "," +
                     std::to_string(report.bodies) + "," + std::to_string(report.threads) + "," +
                     std::to_string(report.steps) + "," + std::to_string(report.solver.iterations) + "," +
                     std::to_string(report.solver.substeps) + ",";
  if (!report.skipped.empty()) {
    line += ",,,,,,,," + Quote(report.skipped) + ",";
  } else {
    line += Number(report.totalMs) + "," + Number(report.msMean) + "," + Number(report.msMax) + "," +
            std::to_string(report.maxContacts) + "," + Optional(report.drift) + "," +
            Optional(report.maxPenetration) + "," + Optional(report.kineticEnergy) + "," +
            (report.escaped ? std::to_string(*report.escaped) : "") + ",," + StageField(report.stages);
  }
  if (report.perturbation) {
    // 17 significant digits: the amount reads back as the same double.
    // Appended piece by piece: GCC 12 warns (-Wrestrict) on a chain of
    // temporaries here.
    line.append(",").append(std::to_string(report.perturbation->repeat));
    line.append(",").append(harness::FormatNumber(report.perturbation->amount, 17));
    line.append(",").append(std::to_string(report.perturbation->seed));
  }
  return line;
}

std::string FormatJson(const harness::BenchReport& report) { return harness::BenchReportToJson(report); }

}  // namespace talus::scenes
