// The projectile truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/projectile.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// Free flight on all three axes: the centre of mass follows
/// x0 + v0 t + g t^2 / 2 (g the world's gravity vector); the metric is the
/// largest distance from that parabola over the run (judged against the
/// continuous answer, not an integrator's sequence).
struct ProjectileTruth {
  static constexpr std::string_view kName = "projectile";
  Vec3 x0 = Vec3::Zero();  ///< metres, centre of mass at t = 0
  Vec3 v0 = Vec3::Zero();  ///< m/s
  bool operator==(const ProjectileTruth&) const = default;

  static std::string_view Schema();
  static Result<ProjectileTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth, const ProjectileTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
