// CollideShapes: the narrow phase for one pair of shapes at two poses,
// without a World (in the spirit of Box2D's b2CollidePolygons and Jolt's
// CollideShape).
//
// Units and conventions are the engine's: metres, world space, and the
// normal points from B towards A (push A along +normal and B along -normal
// to separate them), as in the write-up and ContactPointInfo. The answer is
// the one a World's contact stage gets for the same pair and settings
// (engine/src/collision/collide.h does the work for both), so a tool that
// checks CollideShapes checks the World's narrow phase.
//
// What it guarantees for two polyhedra (box or hull) that touch, beside the
// SAT's own bounds (docs/collision-narrow-phase.md):
// - `depth` is the SAT's minimum overlap, within kAxisPreferenceRelative x
//   the pair's size of the exact minimum translation distance;
// - no point is deeper than `depth`, and the deepest point's depth equals
//   it (to round-off) unless the SAT's deepest vertex lies outside the
//   other shape: then no point of the intersection is that deep along the
//   normal, and the points carry their own, shallower depths;
// - every point lies inside both shapes (to round-off).
#pragma once

#include <array>
#include <cstdint>

#include "talus/math.h"
#include "talus/narrow_phase.h"
#include "talus/result.h"
#include "talus/shape.h"
#include "talus/transform.h"

namespace talus {

/// Most points a pair query reports (the WriteUp generator's cap; the
/// default Clipped generator gives at most 4).
inline constexpr int kPairQueryMaxPoints = 8;

/// One contact point of a pair query.
struct PairContactPoint {
  Vec3 position = Vec3::Zero();  ///< metres, world space, inside both shapes
  /// Metres along the normal, > 0 when the shapes overlap there; negative
  /// (down to -speculativeMargin) for a speculative point.
  double depth = 0.0;
  /// The two features (vertex, edge or face of A in the high 16 bits, of B
  /// in the low 16) that made this point; stable while the same features
  /// touch, so a caller can match points across frames. The packing is
  /// PairFeatureType (2 bits) then the feature's index (14 bits).
  std::uint32_t featureId = 0;
};

/// The kind of feature in each 16-bit half of a featureId (bits 14-15).
enum class PairFeatureType : std::uint32_t { Vertex = 0, Edge = 1, Face = 2, None = 3 };

/// The answer for one pair.
struct PairContact {
  /// True when the shapes overlap or are within settings.speculativeMargin;
  /// the points are filled only then.
  bool touching = false;
  /// Signed distance along `normal` (metres). Touching: minus the depth
  /// (the minimum overlap; >= -margin..0 for a speculative contact).
  /// Not touching: the gap along the separating axis found, a lower bound
  /// on the distance between the shapes (exact for pairs with a sphere).
  double separation = 0.0;
  /// Unit, world space, from B towards A: the contact normal, or the
  /// separating axis when not touching.
  Vec3 normal = Vec3::UnitY();
  int pointCount = 0;  ///< 0..kPairQueryMaxPoints; 0 when not touching
  std::array<PairContactPoint, kPairQueryMaxPoints> points{};

  /// The overlap (metres, >= 0): -separation when touching, else 0.
  [[nodiscard]] double Depth() const { return touching && separation < 0.0 ? -separation : 0.0; }
};

/// The feature type of one half (A's: `id >> 16`, B's: `id & 0xFFFF`) of a
/// featureId.
constexpr PairFeatureType FeatureTypeOf(std::uint32_t half) {
  return static_cast<PairFeatureType>((half >> 14) & 0x3u);
}
/// The feature index of one half of a featureId (wraps above 16383).
constexpr int FeatureIndexOf(std::uint32_t half) { return static_cast<int>(half & 0x3FFFu); }

/// Collides shape `a` at pose `xfA` with shape `b` at pose `xfB`.
/// `settings`: SAT mode, manifold mode and speculative margin are used;
/// useSatCache and reuseDistance have no meaning for a single query and are
/// ignored. Refuses, with a message naming the argument, a non-finite
/// position, a rotation that is not a unit quaternion (|q| off 1 by more
/// than 1e-6) and a margin that is negative or not finite; never returns a
/// partial answer.
Result<PairContact> CollideShapes(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                                  const NarrowPhaseSettings& settings = {});

}  // namespace talus
