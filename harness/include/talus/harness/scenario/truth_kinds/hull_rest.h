// The hull_rest truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/hull_rest.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// A hull body comes to rest on the face with outward body-frame normal
/// `faceNormal`, a stable face (its centroid projects inside it), with its
/// centre of mass at floor + `height`, the centroid's distance to that face's
/// plane. Both `faceNormal` and `height` are the file's, computed without the
/// engine (qhull facets and a divergence-theorem centroid; tests/reference
/// checks the shipped numbers); the loader only refuses a normal that names
/// no stable face of the hull.
struct HullRestTruth {
  static constexpr std::string_view kName = "hull_rest";
  Vec3 faceNormal = -Vec3::UnitY();  ///< unit, body frame (the file's, normalised)
  double floor = 0.0;                ///< metres, top of the floor along the up axis
  double height = 0.0;               ///< metres, from the file
  double maxFaceAngle = 0.05;        ///< radians: face normal vs down at the end, in [0, pi]
  bool operator==(const HullRestTruth&) const = default;

  static std::string_view Schema();
  static Result<HullRestTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth, const HullRestTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
