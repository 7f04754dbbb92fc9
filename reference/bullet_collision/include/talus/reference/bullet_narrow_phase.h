// Bullet's convex-convex narrow phase called on its own, without a
// collision world: a Talus hull becomes a btConvexHullShape with zero
// collision margin (so its surface is the hull's), and a pair query returns
// Bullet's signed distance, normal and point in Talus's conventions (normal
// from B towards A, signed distance < 0 when penetrating).
//
// Bullet's headers stay private (pimpl), so users of this library need not
// see them nor define BT_USE_DOUBLE_PRECISION.
#pragma once

#include <memory>

#include "talus/hull.h"
#include "talus/math.h"
#include "talus/transform.h"

namespace talus::reference {

/// Which Bullet routine answers the query.
enum class BulletNarrowPhaseMethod {
  /// btGjkPairDetector (Johnson's distance subalgorithm via
  /// btVoronoiSimplexSolver) with btGjkEpaPenetrationDepthSolver for
  /// penetration: what btConvexConvexAlgorithm runs.
  GjkPairDetector,
  /// btGjkEpaSolver2::SignedDistance (Presson's GJK + EPA) directly.
  GjkEpa2,
};

/// A Talus hull as a Bullet convex hull shape (margin 0). Owns the shape.
class BulletHullShape {
 public:
  explicit BulletHullShape(const Hull& hull);
  ~BulletHullShape();
  BulletHullShape(const BulletHullShape&) = delete;
  BulletHullShape& operator=(const BulletHullShape&) = delete;

  struct Impl;
  [[nodiscard]] const Impl& Get() const { return *m_impl; }

 private:
  std::unique_ptr<Impl> m_impl;
};

/// One Bullet answer.
struct BulletAnswer {
  bool ok = true;               ///< false: Bullet reported a failure or no result
  bool intersecting = false;    ///< signedDistance < 0
  double signedDistance = 0.0;  ///< metres: gap > 0, minus the depth < 0
  Vec3 normal = Vec3::Zero();   ///< unit, from B towards A
  Vec3 point = Vec3::Zero();    ///< world: midway between Bullet's two witness points
};

/// Queries the pair A (at xfA) and B (at xfB) with `method`.
BulletAnswer BulletPairQuery(const BulletHullShape& a, const Transform& xfA, const BulletHullShape& b,
                             const Transform& xfB, BulletNarrowPhaseMethod method);

}  // namespace talus::reference
