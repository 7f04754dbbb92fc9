// ContactManifold: what the narrow phase hands the solver for one touching
// pair of shapes A and B.
//
// Invariants: `normal` is a world-space unit vector pointing from B towards
// A (push A along +normal, B along -normal to separate them); `depth` is the
// SAT's minimum overlap along it; 0 <= pointCount <= kMaxManifoldPoints and
// only points[0, pointCount) are meaningful. A point's featureId names the
// two features (vertex, edge or face of A and of B) that made it, packed by
// MakeFeatureId, so the solver can match points across steps for warm
// starting. This layout is a contract with the solver: change it only
// together with engine/src/dynamics.
#pragma once

#include <array>
#include <cstdint>

#include "talus/math.h"

namespace talus {

/// Most points a manifold can hold (the WriteUp generator's cap; the
/// Clipped generator keeps at most 4).
inline constexpr int kMaxManifoldPoints = 8;

struct ContactPoint {
  Vec3 position;  // world space, metres: midway between the two surfaces
  double depth;   // metres, > 0 when penetrating (may be slightly negative within a speculative margin)
  std::uint32_t featureId;  // which features of A and B made this point, stable across steps
};
// Eight points are 320 of ContactManifold's 360-byte budget (dynamics/
// contact.h); every stage after the narrow phase copies or walks them
// (docs/collision-narrow-phase.md, Record sizes).
static_assert(sizeof(ContactPoint) == 40, "ContactPoint: position, depth, feature id (padded to 8)");

struct ContactManifold {
  Vec3 normal;   // world space unit normal, pointing from B towards A
  double depth;  // the SAT's minimum overlap (metres); no point is deeper
  int pointCount;
  std::array<ContactPoint, kMaxManifoldPoints> points;
};

/// The kind of feature half of a featureId names.
enum class FeatureType : std::uint32_t {
  Vertex = 0,
  Edge = 1,  ///< an edge index (half-edges 2e and 2e + 1)
  Face = 2,
  None = 3,  ///< no feature on this shape (e.g. a sphere's centre)
};

/// Packs one shape's feature into 16 bits: 2 bits of type, 14 bits of
/// index. Indices above 16383 wrap, so on huge hulls two features may share
/// an id; ids then only lose warm-starting, never correctness.
constexpr std::uint32_t PackFeature(FeatureType type, int index) {
  return (static_cast<std::uint32_t>(type) << 14) | (static_cast<std::uint32_t>(index) & 0x3FFFu);
}

/// A contact point's id: A's feature in the high 16 bits, B's in the low.
constexpr std::uint32_t MakeFeatureId(std::uint32_t featureA, std::uint32_t featureB) {
  return (featureA << 16) | (featureB & 0xFFFFu);
}

/// The id the same point gets when A and B swap roles.
constexpr std::uint32_t SwapFeatureId(std::uint32_t id) { return (id << 16) | (id >> 16); }

}  // namespace talus
