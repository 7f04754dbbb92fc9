// The sliding_stop truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/sliding_stop.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// A body launched at v0 (m/s) on a floor with friction mu stops after
/// v0^2 / (2 mu g) metres and v0 / (mu g) seconds, on the straight line
/// through its start along `direction`.
struct SlidingStopTruth {
  static constexpr std::string_view kName = "sliding_stop";
  double v0 = 1.0, mu = 0.5, g = 9.81;
  Vec3 direction = Vec3::UnitX();  ///< unit, world frame, perpendicular to gravity
  double maxLateral = 0.01;        ///< metres: largest allowed distance from the launch line, >= 0
  bool operator==(const SlidingStopTruth&) const = default;

  static std::string_view Schema();
  static Result<SlidingStopTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth, const SlidingStopTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
