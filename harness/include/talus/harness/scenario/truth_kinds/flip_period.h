// The flip_period truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/flip_period.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// The same body spun mainly about its intermediate axis turns over every
/// IntermediateAxisFlipInterval(inertia, omega) seconds (torque_free_motion.h).
struct FlipPeriodTruth {
  static constexpr std::string_view kName = "flip_period";
  Vec3 inertia = Vec3::Ones();
  Vec3 omega = Vec3::Zero();
  bool operator==(const FlipPeriodTruth&) const = default;

  static std::string_view Schema();
  static Result<FlipPeriodTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth, const FlipPeriodTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
