// A hand-made run of one sweep instance whose error scalar is exactly
// `error`: one checked metric whose truth is 0 and whose measured value is
// `error`, with an absolute tolerance of 1, and a total wall time of
// `seconds` over 10 steps (its cost, sweep.h). The sweep analysis tests build
// their fronts from these, so every answer can be read off the numbers.
#pragma once

#include <string>

#include "talus/harness/run/runner.h"
#include "talus/harness/truth/truth_check.h"

namespace talus::harness::sweep_fixture {

inline RunResult OneMetricRun(const std::string& backend, const std::string& hLabel, double h, double seconds,
                              double error) {
  RunResult run;
  run.scenario = "slide";
  run.runId = "slide[h=" + hLabel + "]";
  run.backend = backend;
  run.sweepValues = {{"h", hLabel}};
  run.timeStep = h;
  run.steps = 10;
  run.wallSecondsPerStepMedian = seconds / 10.0;
  run.wallSecondsPerStepMean = seconds / 10.0;
  run.wallSeconds = seconds;
  run.wallSecondsLongestStep = seconds / 10.0;
  MetricResult metric = MakeMetric("m", "m");
  metric.truth = 0.0;
  metric.measured = error;  // the sweep reads the distance to the truth, exactly `error`
  metric.error = error;
  metric.tolerance = {1.0, 0.0};
  metric.checked = true;
  run.metrics = {metric};
  return run;
}

}  // namespace talus::harness::sweep_fixture
