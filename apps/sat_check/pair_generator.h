// The validation's pairs of convex shapes: deterministic from a seed, so
// every run of `talus-sat-check --seed S` sees the same pairs.
//
// A pair is two shapes (a box or a random convex hull each) of varied size
// and aspect ratio, placed along a direction n so that their extents along
// n overlap or leave a gap chosen by the placement class: well separated,
// just touching (within a few nanometres), shallow or deep overlap. The
// alignment class picks the rotations: random; face-aligned (same rotation,
// placed along a face normal of A, so faces are parallel); edge-aligned
// (B turned 45 degrees about two of A's axes, so edges cross). The true
// gap or depth is not the one aimed at along n: the truth decides.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "talus/shape.h"
#include "talus/transform.h"

namespace talus::validation {

/// Where B is put relative to A.
enum class Placement { Separated, Touching, Shallow, Deep };
/// How the two rotations relate.
enum class Alignment { Random, Face, Edge };

/// The names used in the JSON and Markdown reports.
const char* ToString(Placement placement);
const char* ToString(Alignment alignment);

/// One generated pair and how it was made.
struct ShapePair {
  int index = 0;
  Shape a;
  Shape b;
  Transform xfA;
  Transform xfB;
  Placement placement = Placement::Separated;
  Alignment alignment = Alignment::Random;
  double targetGap = 0.0;  ///< metres along the placement direction (< 0: overlap)
  double size = 0.0;       ///< metres: the smaller of the two shapes' largest half extents
};

/// Makes `count` pairs from `seed`. Shapes: half the pairs' shapes are
/// boxes, half hulls of 8 to 64 points on an ellipsoid; largest half
/// extents log-uniform in [0.1, 2] m, aspect ratios in [0.2, 1].
std::vector<ShapePair> GeneratePairs(int count, std::uint64_t seed);

/// A short readable description ("box 0.31x0.12x0.2 vs hull 32v, face, deep").
std::string Describe(const ShapePair& pair);

}  // namespace talus::validation
