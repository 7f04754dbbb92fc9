// ContactManifold: what the narrow phase hands the solver for one touching
// pair (A, B). The normal points from B towards A; depths are positive when
// the shapes penetrate. Feature ids name the features of A and B that made
// each point and stay the same while the same features touch, so the solver
// can carry a point's impulses from one step to the next (warm starting).
#pragma once

#include <array>
#include <cstdint>

#include "talus/math.h"

namespace talus {

/// Most points a manifold holds (a face clipped against a face).
inline constexpr int kMaxManifoldPoints = 8;

struct ContactPoint {
  Vec3 position;            // world space, metres: midway between the two surfaces
  double depth;             // metres, > 0 when penetrating
  std::uint32_t featureId;  // which features of A and B made this point, stable across steps
};

struct ContactManifold {
  Vec3 normal;   // world space unit normal, pointing from B towards A
  double depth;  // the SAT's minimum overlap (metres)
  int pointCount;
  std::array<ContactPoint, kMaxManifoldPoints> points;
};

}  // namespace talus
