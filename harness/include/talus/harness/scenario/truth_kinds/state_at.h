// The state_at truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/state_at.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// Which part of a body's state a state_at truth judges.
enum class StateQuantity {
  Position,     ///< centre of mass, metres, world
  Velocity,     ///< centre of mass velocity, m/s, world
  Orientation,  ///< of the body frame, a unit quaternion (w, x, y, z)
};

/// `body`'s state at time `time` (seconds) against a stated value: the
/// metric is the distance |measured - value| (metres or m/s), or for an
/// orientation the angle of the rotation between them (radians), judged
/// against the tolerance (absolute). Between recorded samples the state is
/// interpolated (linearly, or by slerp for an orientation).
struct StateAtTruth {
  static constexpr std::string_view kName = "state_at";
  StateQuantity quantity = StateQuantity::Position;
  double time = 0.0;          ///< seconds, in [0, the run's end]
  Vec3 value = Vec3::Zero();  ///< position or velocity
  /// For Orientation: (w, x, y, z) as written, unit to 1e-6 (the
  /// evaluator normalises it; kept as written so a file reloads the same).
  Eigen::Vector4d orientation = Eigen::Vector4d(1.0, 0.0, 0.0, 0.0);
  bool operator==(const StateAtTruth&) const = default;

  static std::string_view Schema();
  static Result<StateAtTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth, const StateAtTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
