// The torque_free truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/torque_free.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// Torque-free rotation (no gravity, no contact) of a body with principal
/// moments `inertia` (kg m^2, about its body axes) spinning at `omega`
/// (rad/s, body frame, at the start): world angular momentum and kinetic
/// energy stay constant.
struct TorqueFreeTruth {
  static constexpr std::string_view kName = "torque_free";
  Vec3 inertia = Vec3::Ones();
  Vec3 omega = Vec3::Zero();
  bool operator==(const TorqueFreeTruth&) const = default;

  static std::string_view Schema();
  static Result<TorqueFreeTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth, const TorqueFreeTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
