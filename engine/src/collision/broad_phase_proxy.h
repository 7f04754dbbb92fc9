// Broad phase proxies, pairs and tunables: the vocabulary every broad phase
// structure shares.
//
// A proxy stands for one body slot: proxy i is body slot i, so the proxy
// array may hold inactive slots (removed bodies) that every structure skips.
// The pair test is defined once here (SpheresTouch) so that all structures
// report exactly the same set; the box every structure bins or nests a proxy
// by (ProxyBox) is padded by a hair so that any two touching spheres always
// have overlapping boxes despite rounding. All tunables of the broad phase
// live in this file, each with its unit and reason.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "talus/broad_phase.h"
#include "talus/math.h"

namespace talus {

/// One body's bounding volume as the broad phase sees it.
struct BroadPhaseProxy {
  Sphere sphere;          ///< world-space centre (m) and radius (m, >= 0)
  bool isStatic = false;  ///< static-static pairs are never reported
  bool active = true;     ///< false for an empty body slot: ignored
};
// One per body, rewritten every step and read by every structure's pass
// (docs/collision-broad-phase.md, Record sizes).
static_assert(sizeof(BroadPhaseProxy) == 40, "BroadPhaseProxy: a 32-byte sphere and two flags");

/// A pair of body slots whose bounding spheres touch, a < b.
struct BroadPhasePair {
  int a = -1;
  int b = -1;
  friend bool operator==(const BroadPhasePair&, const BroadPhasePair&) = default;
  friend bool operator<(const BroadPhasePair& l, const BroadPhasePair& r) {
    return l.a != r.a ? l.a < r.a : l.b < r.b;
  }
};
// Eight to a cache line: the pair list is sorted and walked every step
// (docs/collision-broad-phase.md, Record sizes).
static_assert(sizeof(BroadPhasePair) == 8, "BroadPhasePair: two int slots");

/// Worlds with at most this many active proxies use brute force whatever
/// structure is selected: below it building a grid or walking a tree costs
/// more than testing the n(n-1)/2 pairs. Measured (bench BM_TinyWorld, 1 m
/// bodies, moving): brute force 16.6 us vs grid 20.9 us at 128 bodies, 62 us
/// vs 45 us at 256; see docs/collision-broad-phase.md. Unit: proxies. The
/// value is public (talus/broad_phase.h) so callers can name it.
inline constexpr int kTinyWorldProxies = kTinyWorldBodies;

/// Grid cell edge = kCellSizeFactor x the largest dynamic bounding-sphere
/// diameter. 1 is the write-up's rule "at least as large as the largest
/// object, but not much larger": every dynamic body then overlaps at most
/// 2x2x2 cells. Unitless, >= 1.
inline constexpr double kCellSizeFactor = 1.0;

/// Smallest grid cell edge (m): keeps cell coordinates finite when every
/// dynamic body is a point (radius 0).
inline constexpr double kMinCellSize = 1e-6;

/// A body whose bounding-sphere diameter exceeds kOversizedCellSpan cells is
/// not binned (it would fill up to (span + 1)^3 cells, e.g. a 100 m floor
/// under 1 m cubes would fill ~10^5): it goes to the oversized list and is
/// sphere-tested against every body instead. Unitless (cells).
inline constexpr double kOversizedCellSpan = 4.0;

/// AABB tree: a leaf's box is the body's box enlarged by this fraction of its
/// radius on every side, so a body that moves less than that keeps its leaf
/// (no reinsertion). Unitless.
inline constexpr double kTreeMarginFraction = 0.2;

/// AABB tree: absolute part of the enlargement (m), so points and tiny
/// bodies get some slack too.
inline constexpr double kTreeMarginAbsolute = 0.01;

/// Largest accepted |coordinate| of a proxy centre and largest radius (m):
/// beyond it grid cell coordinates would lose integer precision. A body that
/// far out has left any simulation the testbed runs.
inline constexpr double kMaxWorldCoordinate = 1e9;

/// Relative padding of ProxyBox (unitless): a few thousand ulps, so that the
/// box test never rejects spheres that SpheresTouch accepts.
inline constexpr double kBoxPadding = 1e-12;

/// True when the two spheres touch or overlap (closed test). The one pair
/// test every structure applies, so all report identical sets.
inline bool SpheresTouch(const Sphere& a, const Sphere& b) {
  const double reach = a.radius + b.radius;
  return (a.center - b.center).squaredNorm() <= reach * reach;
}

/// The axis-aligned box a structure bins or nests a proxy by: the sphere's
/// box, padded by kBoxPadding relative to the coordinates' magnitude.
inline Aabb ProxyBox(const Sphere& s) {
  const double pad = kBoxPadding * (s.radius + s.center.cwiseAbs().maxCoeff());
  const Vec3 half = Vec3::Constant(s.radius + pad);
  return {s.center - half, s.center + half};
}

/// Closed overlap test of two boxes.
inline bool BoxesOverlap(const Aabb& a, const Aabb& b) {
  return a.min.x() <= b.max.x() && b.min.x() <= a.max.x() && a.min.y() <= b.max.y() &&
         b.min.y() <= a.max.y() && a.min.z() <= b.max.z() && b.min.z() <= a.max.z();
}

}  // namespace talus
