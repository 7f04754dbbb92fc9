// The exact penetration truth for two convex polyhedra, independent of any
// SAT, GJK or EPA: the Minkowski difference D = A - B is the convex hull of
// every difference a_i - b_j of world vertices, and A and B intersect iff
// the origin lies in D. When it does, the least translation that separates
// them is the distance from the origin to D's boundary, which for a convex
// polytope containing the origin is the smallest face-plane offset; the
// face that attains it gives the direction. When it does not, the distance
// between A and B is the distance from the origin to D (closest point over
// D's triangulated faces).
//
// Conventions (docs/ARCHITECTURE.md): the normal points from B towards A,
// i.e. it is the way A must move. Moving A by t*n moves D by t*n, so the
// origin leaves D through its face of outward normal m when n = -m.
//
// D is built with qhull (Barber, Dobkin and Huhdanpaa; reference/qhull),
// not with the engine's own hull builder, so the truth shares no code with
// the engine. CheckMinkowskiWithQhull cross-checks it against a second
// builder (talus::BuildHull): same volume, each hull inside the other, so
// a bug in either cannot pass silently into the truth.
#pragma once

#include <vector>

#include "talus/hull.h"
#include "talus/math.h"
#include "talus/result.h"
#include "talus/transform.h"

namespace talus::reference {

/// The exact answer for one pair.
struct PenetrationTruth {
  bool intersecting = false;  ///< origin inside D (boundary counts as inside)
  /// Signed distance between A and B in metres: the gap (> 0) when
  /// separated, minus the penetration depth (<= 0) when intersecting.
  double signedDistance = 0.0;
  /// Unit, from B towards A: the minimum-depth direction when intersecting,
  /// the direction from B's closest point to A's when separated.
  Vec3 normal = Vec3::UnitY();
  int differenceVertices = 0;  ///< vertices of D
  int differenceFaces = 0;     ///< faces of D (distinct facet planes)
  /// Faces of D whose plane offset is within 1e-9 m of the minimum: more
  /// than one means the minimum direction is not unique (a tie).
  int minimumFaces = 0;

  /// Penetration depth in metres (0 when separated).
  [[nodiscard]] double Depth() const { return intersecting ? -signedDistance : 0.0; }
};

/// All |A| x |B| world-space vertex differences a_i - b_j (i major).
std::vector<Vec3> MinkowskiDifferencePoints(const Hull& a, const Transform& xfA, const Hull& b,
                                            const Transform& xfB);

/// The truth for A at xfA and B at xfB, from qhull's hull of the
/// difference points. Fails only if the difference spans no volume (cannot
/// happen for two valid hulls) or a coordinate is not finite, with qhull's
/// message.
Result<PenetrationTruth> ComputePenetrationTruth(const Hull& a, const Transform& xfA, const Hull& b,
                                                 const Transform& xfB);

/// Cross-checks qhull's hull of the difference points (the truth's) against
/// BuildHull's: volumes equal to `relativeTolerance` (default 1e-9), every
/// difference point inside qhull's facets and every corner of those inside
/// BuildHull's hull, both to BuildHull's tolerance plus 64 ulps of the
/// largest coordinate. Returns an error
/// describing the first mismatch.
Result<bool> CheckMinkowskiWithQhull(const Hull& a, const Transform& xfA, const Hull& b, const Transform& xfB,
                                     double relativeTolerance = 1e-9);

/// The point of triangle (a, b, c) closest to `point` (Ericson, Real-Time
/// Collision Detection, 5.1.5: Voronoi regions of vertices, edges, face).
Vec3 ClosestPointOnTriangle(const Vec3& point, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace talus::reference
