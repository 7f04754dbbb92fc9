// The convex hull of a point cloud as an outward triangle mesh, computed by
// qhull (the reentrant C library). The peers need it because ODE's dConvex
// wants planes and polygons and because a hull's mass properties come from
// its boundary; Bullet builds its own polyhedral features from the points.
// Coplanar facets come out as several triangles: harmless for mass
// properties; the ODE backend merges them back into face polygons.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "talus/math.h"
#include "talus/result.h"

namespace talus::reference {

/// A closed convex triangle mesh.
struct PointHull {
  std::vector<Vec3> vertices;                 ///< the hull's vertices only (interior points dropped)
  std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise seen from outside
};

/// The hull of `points` (metres). Fails, naming the problem, when a
/// coordinate is not finite or the points span no volume.
Result<PointHull> ComputePointHull(std::span<const Vec3> points);

}  // namespace talus::reference
