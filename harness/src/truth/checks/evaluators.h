// One evaluator per truth kind, each in its own file next to this header;
// harness/src/truth/truth_check.cpp dispatches to them. Each returns the metrics
// of its kind, judged against the truth's tolerance (Judge), and reads
// sample steps and times from the trajectory, never assuming stride 1.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "talus/harness/truth/truth_check.h"

namespace talus::harness {

std::vector<MetricResult> EvaluateFreeFall(const Run& run, const Truth& truth, const FreeFallTruth& kind,
                                           const Trajectory& trajectory);
std::vector<MetricResult> EvaluateSlidingStop(const Run& run, const Truth& truth,
                                              const SlidingStopTruth& kind, const Trajectory& trajectory);
std::vector<MetricResult> EvaluateRestHeight(const Run& run, const Truth& truth, const RestHeightTruth& kind,
                                             const Trajectory& trajectory);
std::vector<MetricResult> EvaluateBounceHeights(const Run& run, const Truth& truth,
                                                const BounceHeightsTruth& kind, const Trajectory& trajectory);
std::vector<MetricResult> EvaluateStackRest(const Run& run, const Truth& truth, const StackRestTruth& kind,
                                            const Trajectory& trajectory);
std::vector<MetricResult> EvaluateHullRest(const Run& run, const Truth& truth, const HullRestTruth& kind,
                                           const Trajectory& trajectory);
std::vector<MetricResult> EvaluateInclineSlide(const Run& run, const Truth& truth,
                                               const InclineSlideTruth& kind, const Trajectory& trajectory);
std::vector<MetricResult> EvaluateInclineTip(const Run& run, const Truth& truth, const InclineTipTruth& kind,
                                             const Trajectory& trajectory);
std::vector<MetricResult> EvaluateTorqueFree(const Run& run, const Truth& truth, const TorqueFreeTruth& kind,
                                             const Trajectory& trajectory);
std::vector<MetricResult> EvaluateFlipPeriod(const Run& run, const Truth& truth, const FlipPeriodTruth& kind,
                                             const Trajectory& trajectory);
std::vector<MetricResult> EvaluateProjectile(const Run& run, const Truth& truth, const ProjectileTruth& kind,
                                             const Trajectory& trajectory);
std::vector<MetricResult> EvaluateEnergyDrift(const Run& run, const Truth& truth,
                                              const EnergyDriftTruth& kind, const Trajectory& trajectory);
std::vector<MetricResult> EvaluateAngularMomentumDrift(const Run& run, const Truth& truth,
                                                       const AngularMomentumDriftTruth& kind,
                                                       const Trajectory& trajectory);
std::vector<MetricResult> EvaluateBoxLanding(const Run& run, const Truth& truth, const BoxLandingTruth& kind,
                                             const Trajectory& trajectory);

/// The written reason of the truth's secondary bound `field` (e.g.
/// "maxJitter"); empty when the truth has none (one built in code). An
/// evaluator gives it to the metric the bound judges.
std::string BoundReason(const Truth& truth, std::string_view field);

std::vector<MetricResult> EvaluateRotationalEnergyDrift(const Run& run, const Truth& truth,
                                                        const RotationalEnergyDriftTruth& kind,
                                                        const Trajectory& trajectory);

}  // namespace talus::harness
