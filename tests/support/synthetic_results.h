// Synthetic results for the report tests: a judged truth whose pass/fail
// follows from its error against a 0.01 m tolerance, and a run holding such
// truths, so each test can work its expected counts out by hand.
#pragma once

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "talus/harness/run/results_file.h"

namespace talus::testing_support {

/// A truth of 1 m measured as 1 + `error` m, tolerance 0.01 m. `gated` false
/// makes it ungated (still judged, shown as "under study").
inline harness::MetricResult SyntheticTruth(const std::string& name, double error, bool gated = true) {
  harness::MetricResult m;
  m.name = name;
  m.unit = "m";
  m.truth = 1.0;
  m.measured = 1.0 + error;
  m.error = error;
  m.tolerance.absolute = 0.01;
  m.pass = std::abs(error) <= 0.01;
  m.checked = gated;
  if (!gated) m.ungated = "under study";
  return m;
}

/// A 100-step run at h = 0.01 s of scenario runId up to its first '['.
inline harness::RunResult SyntheticRun(const std::string& runId, const std::string& backend,
                                       std::vector<harness::MetricResult> metrics, double secondsPerStep,
                                       const std::string& error = "") {
  harness::RunResult r;
  r.scenario = runId.substr(0, runId.find('['));
  r.file = "x.json";
  r.runId = runId;
  r.backend = backend;
  r.timeStep = 0.01;
  r.steps = 100;
  r.wallSecondsPerStepMedian = secondsPerStep;
  r.metrics = std::move(metrics);
  r.error = error;
  return r;
}

}  // namespace talus::testing_support
