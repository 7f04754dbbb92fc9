// The accuracy gate (regression_check.h): re-derives what the checkout's
// scenarios expect of each run, refuses a results file that is not the
// checkout's, recomputes every verdict from the measured values and words
// every failure with the numbers a reader needs to judge it.
#include "talus/harness/report/regression_check.h"

#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "support/text_util.h"
#include "talus/harness/backend/trajectory.h"
#include "talus/harness/run/run_metrics.h"
#include "talus/harness/truth/truth_check.h"

namespace talus::harness {
namespace {

// Refusals beyond this many are counted, not listed: one wrong checkout
// can differ in every run.
constexpr std::size_t kMostRefusalsListed = 20;

// The run standing still at its initial state, sampled as the runner
// samples it: what the evaluators need to name their metrics and size
// their tolerances (which depend on the run's step and sampling, never on
// the motion).
Trajectory StandIn(const Run& run) {
  Trajectory trajectory;
  trajectory.timeStep = run.timeStep;
  trajectory.stride = SampleStride(run.steps, RunnerOptions{}.maxSamples);
  Sample still;
  for (const BodySpec& body : run.scenario.bodies) {
    BodyReading reading;
    reading.centerOfMass = body.position;
    reading.origin = body.position;
    reading.orientation = body.orientation;
    reading.linearVelocity = body.linearVelocity;
    reading.angularVelocity = body.angularVelocity;
    reading.mass = body.motion == Motion::Dynamic ? 1.0 : 0.0;
    reading.worldInertia = body.motion == Motion::Dynamic ? Mat3(Mat3::Identity()) : Mat3(Mat3::Zero());
    still.bodies.push_back(reading);
  }
  for (int step = 0; step <= run.steps; ++step) {
    if (step > 0 && !IsSampled(step, run.steps, trajectory.stride)) continue;
    still.step = step;
    still.time = step * run.timeStep;
    trajectory.samples.push_back(still);
  }
  return trajectory;
}

std::string ToleranceText(const Tolerance& tolerance) {
  return Concat(
      {"absolute ", FormatNumber(tolerance.absolute), ", relative ", FormatNumber(tolerance.relative)});
}

double Reference(const MetricResult& metric) {
  return std::isnan(metric.truthIntegrator) ? metric.truth : metric.truthIntegrator;
}

}  // namespace

std::vector<ExpectedMetric> ExpectedMetrics(const Run& run, std::string_view backend) {
  const Trajectory still = StandIn(run);
  std::vector<ExpectedMetric> expected;
  for (const Truth& truth : run.scenario.truths) {
    // The runner's own order and gating (runner.cpp RunOne).
    std::vector<MetricResult> metrics = std::holds_alternative<ConvergedReferenceTruth>(truth.kind)
                                            ? CompareWithReference(truth, still, still)
                                            : EvaluateTruth(run, truth, still);
    ApplyGate(truth, backend, metrics);
    for (const MetricResult& metric : metrics) {
      expected.push_back({metric.name, metric.tolerance, metric.checked, metric.ungated});
    }
  }
  return expected;
}

bool RecomputedPass(const MetricResult& metric, const Tolerance& tolerance) {
  // incline_tip.cpp's outcome test: tipped means turned beyond the bound.
  if (metric.name.starts_with("incline_tip.tilt.")) {
    return metric.name == "incline_tip.tilt.tips" ? metric.measured > tolerance.absolute
                                                  : metric.measured < tolerance.absolute;
  }
  // Written so that a NaN measured, truth or tolerance fails.
  return std::abs(metric.measured - Reference(metric)) <=
         tolerance.absolute + tolerance.relative * std::abs(metric.truth);
}

namespace {

// What makes a results file not the checkout's, in the order found: the
// first kMostRefusalsListed listed, the rest counted.
class Refusals {
 public:
  void Add(std::string line) {
    if (m_count++ < kMostRefusalsListed) m_lines.push_back(std::move(line));
  }
  [[nodiscard]] bool Any() const { return m_count > 0; }
  [[nodiscard]] Error ToError() const {
    std::string message = "the results file does not match this checkout's scenarios:";
    for (const std::string& line : m_lines) message.append("\n  ").append(line);
    if (m_count > m_lines.size()) {
      message.append("\n  (and ").append(std::to_string(m_count - m_lines.size())).append(" more)");
    }
    return Error{message};
  }

 private:
  std::vector<std::string> m_lines;
  std::size_t m_count = 0;
};

using RunsById = std::map<std::string, const Run*>;

// The checkout's runs by id; a run without a truth is refused, since the
// gate would pass it on 0 metrics.
RunsById IndexRunsWithTruth(const std::vector<Run>& runs, Refusals& refusals) {
  RunsById byId;
  for (const Run& run : runs) {
    byId.try_emplace(run.id, &run);
    if (run.scenario.truths.empty()) {
      refusals.Add(Concat({run.id, " (", run.scenario.file,
                           "): the scenario has no truth, so the gate would pass it on 0 metrics"}));
    }
  }
  return byId;
}

// Refuses results of runs the checkout does not have and runs given twice
// on one backend; returns the (run, backend) pairs the file holds.
std::set<std::pair<std::string, std::string>> RefuseForeignOrRepeatedResults(const ResultsFile& file,
                                                                             const RunsById& byId,
                                                                             Refusals& refusals) {
  std::set<std::pair<std::string, std::string>> present;
  for (const RunResult& result : file.results) {
    if (!byId.contains(result.runId)) {
      refusals.Add(Concat({"the file has run ", result.runId, " (", result.file, ") on ", result.backend,
                           ", which the checkout's scenarios do not have"}));
    }
    if (!present.insert({result.runId, result.backend}).second) {
      refusals.Add(Concat({"the file has run ", result.runId, " on ", result.backend, " twice"}));
    }
  }
  return present;
}

// Refuses every run a checked backend runs in the checkout but the file
// lacks.
void RefuseMissingRuns(const std::vector<Run>& runs, const std::vector<std::string>& backends,
                       const BackendRegistry& registry,
                       const std::set<std::pair<std::string, std::string>>& present, Refusals& refusals) {
  for (const std::string& backend : backends) {
    for (const Run& run : runs) {
      auto ranOn = BackendsForRun(registry, run, {backend});
      if (!ranOn) {
        refusals.Add(ranOn.GetError().message);
        continue;
      }
      if (!ranOn.Value().empty() && !present.contains({run.id, backend})) {
        refusals.Add(
            Concat({"run ", run.id, " (", run.scenario.file, ") on ", backend, " is missing from the file"}));
      }
    }
  }
}

// The verdict of one gated or ungated metric whose name and tolerance are
// the checkout's: counted, and a failure worded with the numbers a reader
// needs to judge it.
void JudgeMetric(const RunResult& result, const MetricResult& m, const ExpectedMetric& e,
                 CheckOutcome& outcome) {
  const bool pass = RecomputedPass(m, e.tolerance);
  if (!e.ungated.empty()) {
    outcome.ungated.push_back(
        Concat({result.runId, " ", m.name, ": ", pass ? "ok" : "FAIL", " (ungated: ", e.ungated, ")"}));
    return;
  }
  if (!e.checked) return;
  ++outcome.checkedMetrics;
  if (pass) return;
  ++outcome.failedMetrics;
  const double allowed = e.tolerance.absolute + e.tolerance.relative * std::abs(m.truth);
  const double error = m.measured - Reference(m);
  const std::string unit = m.unit.empty() ? "" : Concat({" ", m.unit});
  if (std::isnan(m.measured)) {
    outcome.problems.push_back(Concat(
        {result.runId, " ", m.name, ": not measured (expected ", FormatNumber(Reference(m)), unit, ")"}));
    return;
  }
  outcome.problems.push_back(Concat(
      {result.runId, " ", m.name, ": measured ", FormatNumber(m.measured), unit, ", expected ",
       FormatNumber(Reference(m)), unit, " (+- ", FormatNumber(allowed), "), off by ", FormatNumber(error),
       unit, ", ", FormatNumber(std::abs(error) - allowed), unit, " beyond the tolerance"}));
}

// One result's metrics against what the checkout's scenario expects of
// the run: a name, tolerance or count that differs is refused, the rest
// judged.
void CheckResultMetrics(const RunResult& result, const Run& run, const std::string& backend,
                        CheckOutcome& outcome, Refusals& refusals) {
  const std::vector<ExpectedMetric> expected = ExpectedMetrics(run, backend);
  for (std::size_t i = 0; i < result.metrics.size(); ++i) {
    const MetricResult& m = result.metrics[i];
    if (i >= expected.size()) {
      // The runner's reported-only quantities (drift, penetration,
      // contacts) follow the truths and have no tolerance.
      if (m.tolerance.absolute != 0.0 || m.tolerance.relative != 0.0) {
        refusals.Add(Concat({result.runId, " on ", backend, ": metric ", m.name,
                             " has a tolerance that no truth of the checkout's scenario gives"}));
      }
      continue;
    }
    const ExpectedMetric& e = expected[i];
    if (m.name != e.name) {
      refusals.Add(Concat({result.runId, " on ", backend, ": metric ", std::to_string(i), " is ", m.name,
                           " in the file, ", e.name, " in the checkout's scenario"}));
      continue;
    }
    if (!(m.tolerance == e.tolerance)) {
      refusals.Add(
          Concat({result.runId, " on ", backend, " ", m.name, ": tolerance ", ToleranceText(m.tolerance),
                  " in the file, ", ToleranceText(e.tolerance), " in the checkout's scenario"}));
      continue;
    }
    JudgeMetric(result, m, e, outcome);
  }
  if (result.metrics.size() < expected.size()) {
    refusals.Add(
        Concat({result.runId, " on ", backend, ": ", std::to_string(result.metrics.size()),
                " metrics in the file, but the checkout's truths give ", std::to_string(expected.size())}));
  }
}

// Every result of one backend: a run stepped otherwise than the checkout
// says is refused, a failed run is a problem, the rest have their metrics
// checked.
CheckOutcome CheckBackend(const ResultsFile& file, const RunsById& byId, const std::string& backend,
                          Refusals& refusals) {
  CheckOutcome outcome;
  for (const RunResult& result : file.results) {
    if (result.backend != backend) continue;
    ++outcome.runs;
    const auto found = byId.find(result.runId);
    if (found == byId.end()) continue;  // refused by RefuseForeignOrRepeatedResults
    const Run& run = *found->second;
    if (run.steps != result.steps || run.timeStep != result.timeStep) {
      refusals.Add(Concat({result.runId, " on ", backend, ": ", std::to_string(result.steps), " steps of ",
                           FormatNumber(result.timeStep), " s in the file, ", std::to_string(run.steps),
                           " of ", FormatNumber(run.timeStep), " s in the checkout's scenario"}));
      continue;
    }
    if (!result.error.empty()) {
      outcome.problems.push_back(Concat({result.runId, ": the run failed: ", result.error}));
      continue;
    }
    CheckResultMetrics(result, run, backend, outcome, refusals);
  }
  return outcome;
}

}  // namespace

Result<std::vector<CheckOutcome>> RecheckResults(const ResultsFile& file, const std::vector<Run>& runs,
                                                 const std::vector<std::string>& backends,
                                                 const BackendRegistry& registry) {
  Refusals refusals;
  const RunsById byId = IndexRunsWithTruth(runs, refusals);
  const auto present = RefuseForeignOrRepeatedResults(file, byId, refusals);
  RefuseMissingRuns(runs, backends, registry, present, refusals);
  std::vector<CheckOutcome> outcomes;
  for (const std::string& backend : backends) outcomes.push_back(CheckBackend(file, byId, backend, refusals));
  if (refusals.Any()) return refusals.ToError();
  return outcomes;
}

std::span<const UngatedVariant> UngatedTalusVariants() {
  // The soft step is a solver under construction, not the engine's default:
  // its measured FAILs (bounce apexes 0.6-5.6 mm low from restitution
  // applied after the sub-steps, box_slide 1.5 mm long against the
  // symplectic-Euler sum at the scenario's step rather than its sub-step)
  // are its results, shown in the report (docs/dynamics.md, "The soft step").
  static constexpr UngatedVariant kUngated[] = {
      {"talus-soft",
       "the soft step solver, an option under construction and not WorldSettings{}: its FAILs are "
       "results the report shows (docs/dynamics.md, \"The soft step\")"},
      {"talus-manifold",
       "friction per manifold, an option measured against the default and not WorldSettings{}: it "
       "drops heavy_box_on_pyramid at 1000:1, as per-point rows do (docs/dynamics.md, \"Friction per "
       "manifold\")"},
  };
  return kUngated;
}

std::vector<std::string> TalusVariants(const std::vector<std::string>& registered) {
  std::vector<std::string> variants;
  for (const std::string& name : registered) {
    if (name != "talus" && name.rfind("talus-", 0) != 0) continue;
    bool ungated = false;
    for (const UngatedVariant& variant : UngatedTalusVariants()) ungated = ungated || variant.name == name;
    if (!ungated) variants.push_back(name);
  }
  return variants;
}

}  // namespace talus::harness
