// Building a Hull from a point cloud with Quickhull (section 1 of the
// original write-up).
#pragma once

#include <span>

#include "talus/hull.h"
#include "talus/hull_build_trace.h"
#include "talus/math.h"
#include "talus/result.h"

namespace talus {

/// Settings for BuildHull.
struct HullBuildSettings {
  /// Largest number of hull vertices to keep, for game use: Quickhull stops
  /// adding points once the hull has this many, so the result is the hull of
  /// the `maxVertices` most significant extreme points (a subset of the
  /// input). 0 means no cap; otherwise at least 4.
  int maxVertices = 0;

  /// Distance tolerance in metres below which a point counts as on a plane;
  /// 0 (default) derives it from the input's extent with
  /// Hull::DefaultTolerance, which is what nearly every caller wants; a
  /// smaller value is raised to that one (it is the rounding of a plane
  /// distance at the input's coordinates, so nothing finer can hold). This
  /// is the starting tolerance: when the input is noisy at a larger scale
  /// the builder widens it (see BuildHull) and the hull's Tolerance()
  /// reports the one it was built and validated with.
  double tolerance = 0.0;

  /// When not null, BuildHull clears `*trace` and records every iteration
  /// into it (talus/hull_build_trace.h), for figures; default null (no cost).
  HullBuildTrace* trace = nullptr;
};

/// The convex hull of `points` by Quickhull: start from a tetrahedron of
/// extreme points, repeatedly add the farthest outside point of a face,
/// find the horizon through the half-edge structure, replace the visible
/// faces by a cone to the new point, and drop points now inside. Coplanar
/// triangles are merged into polygonal faces.
///
/// Every hull vertex is one of the input points, unchanged. For any input it
/// returns a valid hull or an error, and it always ends (every loop is
/// bounded). It fails (never crashes, never returns an invalid hull) when
/// the points span no volume (fewer than 4 distinct points, all collinear
/// or coplanar within the tolerance); when a coordinate is NaN, infinite or
/// larger than 1e150 m in magnitude (squared distances would overflow);
/// when the set spans less than 1e-140 m (they would underflow); or, as a
/// last resort, when no tolerance up to the widened one below settles into
/// a valid hull. The message names the problem and, for bad values, the
/// point index and the limit.
///
/// Noisy input: points that are coplanar only up to noise well above the
/// tolerance (near-flat clusters; differences of coordinates far from the
/// origin, which carry rounding noise of eps x the original magnitudes that
/// the builder cannot see) may not settle into faces that are planar within
/// the tolerance with every point behind them. The build is then repeated
/// with the tolerance widened 4x (at least 4x the measured planarity error),
/// up to 16 times; so is a build whose merges collapsed the surface (a set
/// that is flat at the tolerance although its first tetrahedron was not).
/// For inputs of up to 2e7 points x faces every input point is checked
/// against every face of the result. The returned hull's Tolerance() is the tolerance it was
/// built and validated with: every face vertex lies within it of the face's
/// plane, every input point is at most that far in front of any face, and
/// neighbouring faces differ by more than it.
Result<Hull> BuildHull(std::span<const Vec3> points, const HullBuildSettings& settings = {});

}  // namespace talus
