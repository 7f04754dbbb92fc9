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
//
// Pairs come in families (pair i is of family i mod kFamilyCount), each a
// place where a narrow phase is known to go wrong:
// - standard: the above, sizes 0.1-2 m near the origin;
// - scaled: the same with sizes from 1 mm to 10 m across (half extent
//   log-uniform in [5e-4, 5] m), so absolute tolerances show;
// - far: standard pairs 1e4-1e5 m from the origin (round-off of large
//   coordinates);
// - parallel: face-aligned pairs with B turned by 1e-6 rad about a random
//   axis (nearly parallel faces: a face of A and one of B almost tie);
// - identical: A and B the same shape at the same rotation, B placed along
//   a face normal of A (no sideways offset) to overlap by 1e-5 to 1e-2 of
//   the size along it (every face ties; the truth decides whether a hull's
//   copy touches);
// - slab: a thin box (3.4 x 0.004 x 2.8 m at scale 1, scale 0.25-2)
//   against a 36-point hull, so a deepest vertex can pass through the slab;
// - largeParallel: two large shapes (largest half extent 2-3 m, 4-6 m
//   across), a face of B turned to face a face of A and then twisted by
//   1e-8 to 1e-6 rad (log-uniform) about a random axis (issue 26: the
//   deepest vertex lies beside the reference face, and an independent
//   qhull check found clipped points up to 1.1 m outside a shape).
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

/// Which family of pairs (see above).
enum class Family { Standard, Scaled, Far, Parallel, Identical, Slab, LargeParallel };
inline constexpr int kFamilyCount = 7;

/// LargeParallel: the twist between the two faces is log-uniform in
/// [kLargeParallelTwistMin, kLargeParallelTwistMax] radians, and the
/// shapes' largest half extent is uniform in [2, 3] m.
inline constexpr double kLargeParallelTwistMin = 1e-8;
inline constexpr double kLargeParallelTwistMax = 1e-6;

/// The names used in the JSON and Markdown reports.
const char* ToString(Placement placement);
const char* ToString(Alignment alignment);
const char* ToString(Family family);

/// One generated pair and how it was made.
struct ShapePair {
  int index = 0;
  Shape a;
  Shape b;
  Transform xfA;
  Transform xfB;
  Placement placement = Placement::Separated;
  Alignment alignment = Alignment::Random;
  Family family = Family::Standard;
  double targetGap = 0.0;  ///< metres along the placement direction (< 0: overlap)
  double size = 0.0;       ///< metres: the smaller of the two shapes' largest half extents
  double twist = 0.0;      ///< radians between the placed faces (Parallel, LargeParallel; else 0)
};

/// Makes `count` pairs from `seed`. Standard shapes: half boxes, half
/// hulls of 8 to 64 points on an ellipsoid; largest half extents
/// log-uniform in [0.1, 2] m, aspect ratios in [0.2, 1]; the other
/// families as described above.
std::vector<ShapePair> GeneratePairs(int count, std::uint64_t seed);

/// A short readable description ("box 0.31x0.12x0.2 vs hull 32v, face, deep").
std::string Describe(const ShapePair& pair);

}  // namespace talus::validation
