// Geometric queries on a Hull: support points, containment, ray casts,
// plane classification and bounding volumes. All in the hull's own frame.
#pragma once

#include <optional>

#include "talus/hull.h"
#include "talus/math.h"

namespace talus {

/// The vertex farthest along `direction` (need not be unit length), found by
/// hill climbing over the half-edge graph from `startVertex` (a good guess,
/// e.g. last step's answer, makes it O(1) in practice; valid range
/// [0, VertexCount()), default 0). Ties may return any of the tied
/// vertices; a zero direction returns `startVertex`.
int SupportVertex(const Hull& hull, const Vec3& direction, int startVertex = 0);

/// The same by checking every vertex; the oracle for SupportVertex.
int SupportVertexBruteForce(const Hull& hull, const Vec3& direction);

/// Whether `point` is inside the hull or within `tolerance` (metres, >= 0)
/// of its surface.
bool ContainsPoint(const Hull& hull, const Vec3& point, double tolerance = 0.0);

/// Where a ray first enters the hull.
struct RayHit {
  double distance = 0.0;       ///< metres along the (unit) ray direction
  Vec3 normal = Vec3::Zero();  ///< outward normal of the face hit
  int face = -1;               ///< index of that face
};

/// First hit of the ray origin + t * direction, 0 <= t <= maxDistance,
/// `direction` non-zero (normalised inside; a zero or non-finite direction
/// or origin reports no hit). `maxDistance` in metres along the unit
/// direction. A ray starting inside the hull reports no hit (it never
/// enters); one starting on the surface and pointing inwards hits at 0.
std::optional<RayHit> RayCast(const Hull& hull, const Vec3& origin, const Vec3& direction,
                              double maxDistance);

/// Which side of a plane the hull lies on.
enum class PlaneSide {
  Front,     ///< every vertex in front of the plane (beyond tolerance)
  Back,      ///< every vertex behind it
  Crossing,  ///< vertices on both sides, or touching within tolerance
};

/// Classifies the hull against `plane`, with `tolerance` in metres.
PlaneSide ClassifyPlane(const Hull& hull, const Plane& plane, double tolerance = 0.0);

/// The write-up's bounding sphere: centred on the hull's volume centroid,
/// radius the distance to the farthest vertex. Cheap and stable under
/// rotation about the centroid.
Sphere CentroidBoundingSphere(const Hull& hull);

/// A tighter enclosing sphere (the minimum enclosing sphere of the
/// vertices, up to round-off); never larger than CentroidBoundingSphere.
Sphere TightBoundingSphere(const Hull& hull);

/// The axis-aligned bounding box of the vertices.
Aabb ComputeAabb(const Hull& hull);

}  // namespace talus
