// Contact point reduction: choosing at most N of a manifold's candidate
// points so that the solver gets a small, well-spread set.
//
// The rule (after Gregorius, "Robust contact creation for physics
// simulations", GDC 2015, and Box2D/Box3D): keep the deepest point first
// (it carries the penetration), then the point farthest from it, then
// greedily the point that enlarges the area of the kept points' convex
// hull (in the contact plane) the most. Ties go to the lower candidate
// index, so the result is deterministic.
#pragma once

#include <span>

#include "collision/contact_manifold.h"
#include "talus/math.h"

namespace talus {

/// Writes at most `maxCount` (1..kMaxManifoldPoints) of `candidates` to
/// `out` by the rule above and returns how many; all of them, in order,
/// when there are no more than `maxCount`. `normal` (unit) is the contact
/// plane's normal.
int ReduceContactPoints(std::span<const ContactPoint> candidates, const Vec3& normal, int maxCount,
                        ContactPoint* out);

/// The area (square metres) of the convex hull of `points` (at most
/// kMaxManifoldPoints + 1) projected on the plane with unit normal
/// `normal`; 0 for fewer than three points.
double ContactPolygonArea(std::span<const Vec3> points, const Vec3& normal);

}  // namespace talus
