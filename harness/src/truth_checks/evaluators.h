// One evaluator per truth kind, each in its own file next to this header;
// harness/src/truth_check.cpp dispatches to them. Each returns the metrics
// of its kind, judged against the truth's tolerance (Judge), and reads
// sample steps and times from the trajectory, never assuming stride 1.
#pragma once

#include <vector>

#include "talus/harness/truth_check.h"

namespace talus::harness {

std::vector<MetricResult> EvaluateFreeFall(const Run& run, const Truth& truth, const FreeFallTruth& kind,
                                           const Trajectory& trajectory);
std::vector<MetricResult> EvaluateSlidingStop(const Run& run, const Truth& truth,
                                              const SlidingStopTruth& kind, const Trajectory& trajectory);
std::vector<MetricResult> EvaluateRestHeight(const Run& run, const Truth& truth, const RestHeightTruth& kind,
                                             const Trajectory& trajectory);
std::vector<MetricResult> EvaluateBounceHeights(const Run& run, const Truth& truth,
                                                const BounceHeightsTruth& kind, const Trajectory& trajectory);

}  // namespace talus::harness
