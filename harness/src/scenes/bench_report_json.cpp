// Writing and reading benchmark reports as JSON lines
// (talus/harness/scenes/bench_report_json.h).
#include "talus/harness/scenes/bench_report_json.h"

#include <cmath>

#include "support/json_checker.h"
#include "support/numbers.h"
#include "support/text_util.h"

namespace talus::harness {
namespace {

// Whether `part` <= `whole` within 1e-9 relative: room for the rounding
// of sums of milliseconds, none for a figure that was changed by hand.
bool AtMost(double part, double whole) { return part <= whole * (1.0 + 1e-9); }

// The stage times of an engine that reports them: each stage a non-empty
// name met once, its mean and longest step finite and >= 0, the means adding
// up to no more than the step's mean and no stage's longest step longer
// than the longest step (the stages run inside the timed step).
void ReadStages(JsonChecker& check, const JsonValue& line, const std::string& path, BenchReport& report) {
  const JsonValue* stages = check.Array(line, path, "stages");
  if (stages == nullptr) return;
  const std::string stagesPath = path + ".stages";
  double sumOfMeans = 0.0;
  for (std::size_t i = 0; i < stages->size() && !check.Failed(); ++i) {
    const std::string at = Concat({stagesPath, "[", std::to_string(i), "]"});
    BenchStage stage;
    stage.name = check.Text((*stages)[i], at, "stage");
    stage.msMean = check.Number((*stages)[i], at, "ms_mean", true);
    stage.msMax = check.Number((*stages)[i], at, "ms_max", true);
    if (check.Failed()) return;
    for (const BenchStage& before : report.stages) {
      if (before.name == stage.name) {
        check.Fail(Concat({at, ".stage"}), "a stage named once");
        return;
      }
    }
    if (!AtMost(stage.msMax, report.msMax)) {
      check.Fail(Concat({at, ".ms_max"}), "a longest step no longer than ms_per_step_max");
      return;
    }
    sumOfMeans += stage.msMean;
    report.stages.push_back(std::move(stage));
  }
  if (!check.Failed() && !AtMost(sumOfMeans, report.msMean)) {
    check.Fail(stagesPath, "stage means adding up to at most ms_per_step_mean");
  }
}

// The cost of a run that was made: finite times >= 0 that hang together
// (mean = total / steps, mean <= longest <= total), so a figure edited by
// hand does not pass for a measured one.
void ReadCost(JsonChecker& check, const JsonValue& line, const std::string& path, BenchReport& report) {
  report.totalMs = check.Number(line, path, "total_ms", true);
  report.msMean = check.Number(line, path, "ms_per_step_mean", true);
  report.msMax = check.Number(line, path, "ms_per_step_max", true);
  if (check.Failed()) return;
  if (report.steps < 1) {
    check.Fail(path + ".steps", "at least 1 step in a run that was made");
    return;
  }
  const double mean = report.totalMs / static_cast<double>(report.steps);
  if (!AtMost(report.msMean, mean) || !AtMost(mean, report.msMean)) {
    check.Fail(path + ".ms_per_step_mean", "total_ms / steps");
    return;
  }
  if (!AtMost(report.msMean, report.msMax) || !AtMost(report.msMax, report.totalMs)) {
    check.Fail(path + ".ms_per_step_max", "a longest step between ms_per_step_mean and total_ms");
  }
}

// The figures of a run that was made; `path` is the line's JSON path.
void ReadFigures(JsonChecker& check, const JsonValue& line, const std::string& path, BenchReport& report) {
  ReadCost(check, line, path, report);
  report.maxContacts = check.Count(line, path, "max_contacts");
  if (JsonChecker::Has(line, "drift_m")) report.drift = check.NumberOrNull(line, path, "drift_m");
  if (JsonChecker::Has(line, "max_penetration_m")) {
    report.maxPenetration = check.NumberOrNull(line, path, "max_penetration_m");
  }
  if (JsonChecker::Has(line, "kinetic_energy_j")) {
    report.kineticEnergy = check.NumberOrNull(line, path, "kinetic_energy_j");
  }
  if (JsonChecker::Has(line, "escaped")) report.escaped = check.Count(line, path, "escaped");
  if (JsonChecker::Has(line, "stages")) ReadStages(check, line, path, report);
}

// The solver settings, as BenchSolverProblem accepts them for the engine.
void ReadSolver(JsonChecker& check, const JsonValue& line, const std::string& path, BenchReport& report) {
  report.solver.iterations = check.Count(line, path, "iterations");
  report.solver.substeps = check.Count(line, path, "substeps");
  if (check.Failed()) return;
  if (const auto problem = BenchSolverProblem(report.engine, report.solver)) {
    const char* key = report.solver.substeps < 1 || report.solver.substeps > kBenchMaxSubsteps
                          ? ".substeps"
                          : ".iterations";
    check.Fail(path + key, Concat({"a setting the engine has: ", *problem}).c_str());
  }
}

}  // namespace

std::string BenchReportToJson(const BenchReport& report) {
  nlohmann::ordered_json line;
  line["engine"] = report.engine;
  line["scene"] = report.scene;
  line["parameter"] = report.parameter;
  line["bodies"] = report.bodies;
  line["threads"] = report.threads;
  line["steps"] = report.steps;
  line["iterations"] = report.solver.iterations;
  line["substeps"] = report.solver.substeps;
  if (report.perturbation) {
    line["repeat"] = report.perturbation->repeat;
    line["perturb_m"] = report.perturbation->amount;
    line["perturb_seed"] = report.perturbation->seed;
  }
  if (!report.skipped.empty()) {
    line["skipped"] = report.skipped;
    return line.dump();
  }
  line["total_ms"] = JsonNumber(report.totalMs);
  line["ms_per_step_mean"] = JsonNumber(report.msMean);
  line["ms_per_step_max"] = JsonNumber(report.msMax);
  line["max_contacts"] = report.maxContacts;
  if (report.drift) line["drift_m"] = JsonNumber(*report.drift);
  if (report.maxPenetration) line["max_penetration_m"] = JsonNumber(*report.maxPenetration);
  if (report.kineticEnergy) line["kinetic_energy_j"] = JsonNumber(*report.kineticEnergy);
  if (report.escaped) line["escaped"] = *report.escaped;
  if (!report.stages.empty()) {
    nlohmann::ordered_json stages = nlohmann::ordered_json::array();
    for (const BenchStage& stage : report.stages) {
      stages.push_back({{"stage", stage.name},
                        {"ms_mean", JsonNumber(stage.msMean)},
                        {"ms_max", JsonNumber(stage.msMax)}});
    }
    line["stages"] = std::move(stages);
  }
  return line.dump();
}

Result<std::vector<BenchReport>> ParseBenchReportLines(std::string_view text, std::string_view source) {
  std::vector<BenchReport> reports;
  std::size_t lineNumber = 0;
  for (std::size_t begin = 0; begin < text.size();) {
    const std::size_t end = std::min(text.find('\n', begin), text.size());
    const std::string_view lineText = text.substr(begin, end - begin);
    begin = end + 1;
    ++lineNumber;
    if (lineText.find_first_not_of(" \t\r") == std::string_view::npos) continue;
    const std::string where = Concat({source, ":", std::to_string(lineNumber)});
    const JsonValue line = JsonValue::parse(lineText, nullptr, false);
    if (line.is_discarded()) return Error{Concat({where, ": not valid JSON"})};
    JsonChecker check;
    BenchReport report;
    report.engine = check.Text(line, "$", "engine");
    report.scene = check.Text(line, "$", "scene");
    report.parameter = check.Count(line, "$", "parameter");
    report.bodies = check.Count(line, "$", "bodies");
    report.threads = check.Count(line, "$", "threads");
    report.steps = check.Count(line, "$", "steps");
    ReadSolver(check, line, "$", report);
    if (JsonChecker::Has(line, "skipped")) {
      report.skipped = check.Text(line, "$", "skipped");
    } else {
      ReadFigures(check, line, "$", report);
    }
    if (check.Failed()) return Error{Concat({where, ": ", check.Message()})};
    reports.push_back(std::move(report));
  }
  return reports;
}

Result<std::vector<BenchReport>> ReadBenchReportFile(const std::filesystem::path& path) {
  auto text = ReadTextFile(path, "the benchmark reports");
  if (!text) return text.GetError();
  return ParseBenchReportLines(text.Value(), path.string());
}

}  // namespace talus::harness
