// The qhull oracle: convex hulls from qhull (Barber, Dobkin and Huhdanpaa),
// the independent truth Talus's Quickhull is checked and timed against, and
// the Minkowski differences of the SAT check's truth (QhullFacets).
//
// It wraps qhull's reentrant C API (libqhull_r): each call owns its own qhT,
// sends qhull's messages to a memory buffer (nothing reaches stdout or
// stderr), and frees every qhull allocation before returning, so it runs
// clean under AddressSanitizer and LeakSanitizer.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "talus/math.h"
#include "talus/result.h"

namespace talus {

/// What to compute besides the hull itself.
struct QhullOptions {
  /// Also compute the enclosed volume (qhull's 'FA' pass). Default true; the
  /// benchmark turns it off to time hull construction alone.
  bool computeVolume = true;
};

/// A hull as qhull reports it.
struct QhullHull {
  /// Indices into the input of the hull vertices, ascending.
  std::vector<int> vertexIndices;
  /// Enclosed volume in cubic metres (0 when not computed).
  double volume = 0.0;
  /// Number of facets after qhull's default merging of coplanar facets
  /// (the 'C-0' pre-merge), so polygons count once.
  int facetCount = 0;
};

/// One facet of a triangulated qhull hull: its plane (outward unit
/// normal, offset such that normal . x + offset is the signed distance of
/// x, > 0 outside) and its three corners.
struct QhullFacet {
  Vec3 normal = Vec3::Zero();
  double offset = 0.0;
  std::array<Vec3, 3> corners{};
};

/// The facets of the convex hull of `points` from qhull ("qhull Qt": the
/// default coplanar merging, then each merged facet triangulated; the
/// triangles of one merged facet keep its plane). Fails with qhull's own
/// message as QhullConvexHull does.
Result<std::vector<QhullFacet>> QhullFacets(std::span<const Vec3> points);

/// The convex hull of `points` computed by qhull with default options
/// ("qhull", which merges coplanar facets). Fails with qhull's own message
/// when qhull refuses the input (fewer than 4 points, flat or degenerate
/// sets, NaN).
Result<QhullHull> QhullConvexHull(std::span<const Vec3> points, const QhullOptions& options = {});

}  // namespace talus
