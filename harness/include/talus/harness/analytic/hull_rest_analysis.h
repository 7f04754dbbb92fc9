// Where a convex hull can rest on a floor: for each face, the centre of
// mass's height above the floor when resting on it and whether it is a
// stable face (the centroid projects strictly inside it, so gravity's line
// through the centroid falls inside the support polygon).
//
// The hull and its volume centroid come from the engine's own geometry
// (BuildHull, ComputeMassProperties), so this analysis only validates a
// hull_rest truth in the loader (the named face exists and is stable). The
// truth's answer, the face normal and the height, is written in the
// scenario file and checked against qhull and a divergence-theorem centroid
// that share no code with the engine (tests/reference/hull_rest_truth_test.cpp;
// the harness cannot link qhull: harness <- reference).
#pragma once

#include <span>
#include <vector>

#include "talus/math.h"
#include "talus/result.h"

namespace talus::harness {

/// One face of the hull as a resting face.
struct HullRestFace {
  Vec3 normal = Vec3::UnitY();  ///< outward unit normal, body frame
  double height = 0.0;          ///< metres: distance from the centroid to the face's plane
  double margin = 0.0;          ///< metres: from the centroid's projection to the nearest edge, < 0 outside
  bool stable = false;          ///< margin > 1e-9 times the hull's size
};

/// The faces of a hull with its centroid.
struct HullRestAnalysis {
  Vec3 centroid = Vec3::Zero();  ///< body frame, metres
  std::vector<HullRestFace> faces;

  /// Index of the face whose normal makes the smallest angle with
  /// `direction` (body frame, any length > 0).
  [[nodiscard]] int NearestFace(const Vec3& direction) const;
};

/// Builds the hull of `points` (body frame) and analyses its faces; the
/// builder's error (too few points, flat set, non-finite) is passed on.
Result<HullRestAnalysis> AnalyseHullRest(std::span<const Vec3> points);

}  // namespace talus::harness
