// Bullet's dynamic AABB tree broad phase (btDbvtBroadphase, two trees for
// static and moving proxies, with its persistent hashed pair cache) driven
// directly, for the broad-phase benchmark: one proxy per body, each body's
// box the AABB of its bounding sphere, so Bullet and Talus see the same
// bodies. Bullet's headers stay private (pimpl).
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "talus/math.h"

namespace talus::reference {

/// A btDbvtBroadphase with a fixed set of proxies.
class BulletDbvtBroadPhase {
 public:
  /// One proxy per sphere (centre and radius in metres), proxy i for sphere
  /// i; `isStatic[i]` puts it in Bullet's static filter group (static-static
  /// pairs are never reported, as in Talus). Sizes must match.
  BulletDbvtBroadPhase(std::span<const Sphere> spheres, std::span<const bool> isStatic);
  ~BulletDbvtBroadPhase();
  BulletDbvtBroadPhase(const BulletDbvtBroadPhase&) = delete;
  BulletDbvtBroadPhase& operator=(const BulletDbvtBroadPhase&) = delete;

  /// One step: every proxy's box set from `spheres` (same size and order as
  /// at construction), then calculateOverlappingPairs. Returns the number
  /// of overlapping pairs Bullet then holds.
  std::int64_t Step(std::span<const Sphere> spheres);

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace talus::reference
