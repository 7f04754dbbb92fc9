// Sphere contacts by exact closest features (see sphere_contact.h).
#include "collision/sphere_contact.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace talus {
namespace {

// The closest feature of shape B to the sphere's centre, in B's frame.
struct ClosestFeature {
  Vec3 point;             // on B's surface
  Vec3 normal;            // unit, from B towards the centre (out of B)
  double distance;        // centre = point + distance * normal; < 0 inside
  std::uint32_t feature;  // packed feature of B
};

bool Finish(const ClosestFeature& closest, double radius, const Transform& xfB, double margin,
            ContactManifold* out) {
  const double depth = radius - closest.distance;
  const Vec3 normal = xfB.Rotate(closest.normal);
  out->normal = normal;
  out->depth = depth;
  out->pointCount = 0;
  if (depth < -margin) return false;
  // Midway between B's surface point and the sphere's deepest point.
  const Vec3 local = closest.point + 0.5 * (closest.distance - radius) * closest.normal;
  out->normal = normal;
  out->depth = depth;
  out->pointCount = 1;
  out->points[0] = {.position = xfB.Apply(local),
                    .depth = depth,
                    .featureId = MakeFeatureId(PackFeature(FeatureType::None, 0), closest.feature)};
  return true;
}

ClosestFeature ClosestOnBox(const Vec3& c, const Vec3& e) {
  const Vec3 clamped = c.cwiseMax(-e).cwiseMin(e);
  int clampedAxes = 0;
  std::uint32_t code = 0;
  for (int i = 0; i < 3; ++i) {
    if (clamped[i] != c[i]) {
      ++clampedAxes;
      code |= (c[i] > 0.0 ? 1u : 0u) << i;
    }
  }
  if (clampedAxes == 0) {
    // Inside: leave through the nearest face (ties: lowest axis).
    int axis = 0;
    double best = e[0] - std::abs(c[0]);
    for (int i = 1; i < 3; ++i) {
      if (e[i] - std::abs(c[i]) < best) {
        best = e[i] - std::abs(c[i]);
        axis = i;
      }
    }
    const double sign = c[axis] < 0.0 ? -1.0 : 1.0;
    Vec3 normal = Vec3::Zero();
    normal[axis] = sign;
    Vec3 point = c;
    point[axis] = sign * e[axis];
    // Face index as in Hull::Box: +x, -x, +y, -y, +z, -z.
    return {.point = point,
            .normal = normal,
            .distance = -best,
            .feature = PackFeature(FeatureType::Face, 2 * axis + (sign < 0.0 ? 1 : 0))};
  }
  const Vec3 delta = c - clamped;
  const double distance = delta.norm();
  // Feature: 1 clamped axis = face, 2 = edge, 3 = corner; coded by the
  // clamped axes and their signs (stable, not the Hull's indices).
  const FeatureType type =
      clampedAxes == 1 ? FeatureType::Face : (clampedAxes == 2 ? FeatureType::Edge : FeatureType::Vertex);
  std::uint32_t mask = 0;
  for (int i = 0; i < 3; ++i) mask |= (clamped[i] != c[i] ? 1u : 0u) << i;
  Vec3 normal = distance > kSphereDirectionEpsilon ? Vec3(delta / distance) : Vec3::UnitY();
  return {.point = clamped,
          .normal = normal,
          .distance = distance,
          .feature = PackFeature(type, static_cast<int>(mask << 3 | code))};
}

ClosestFeature ClosestOnHull(const Hull& hull, const Vec3& c) {
  const auto faces = hull.Faces();
  const auto edges = hull.HalfEdges();
  const auto vertices = hull.Vertices();
  int deepest = 0;
  double deepestSeparation = -std::numeric_limits<double>::infinity();
  for (int f = 0; f < hull.FaceCount(); ++f) {
    const double s = faces[static_cast<std::size_t>(f)].plane.SignedDistance(c);
    if (s > deepestSeparation) {
      deepestSeparation = s;
      deepest = f;
    }
  }
  const Plane& deepestPlane = faces[static_cast<std::size_t>(deepest)].plane;
  if (deepestSeparation <= 0.0) {
    return {.point = c - deepestSeparation * deepestPlane.normal,
            .normal = deepestPlane.normal,
            .distance = deepestSeparation,
            .feature = PackFeature(FeatureType::Face, deepest)};
  }
  // Outside: the closest point lies on a face the centre is in front of; on
  // each, it is the projection if that is inside the polygon, else the
  // closest point of the polygon's border.
  ClosestFeature best{.point = Vec3::Zero(),
                      .normal = deepestPlane.normal,
                      .distance = std::numeric_limits<double>::infinity(),
                      .feature = 0};
  for (int f = 0; f < hull.FaceCount(); ++f) {
    const Plane& plane = faces[static_cast<std::size_t>(f)].plane;
    const double s = plane.SignedDistance(c);
    if (s <= 0.0) continue;
    const Vec3 projected = c - s * plane.normal;
    bool inside = true;
    double bestEdge = std::numeric_limits<double>::infinity();
    Vec3 bestEdgePoint = Vec3::Zero();
    std::uint32_t bestEdgeFeature = 0;
    const int first = faces[static_cast<std::size_t>(f)].edge;
    int h = first;
    do {
      const HullHalfEdge& he = edges[static_cast<std::size_t>(h)];
      const Vec3& v0 = vertices[static_cast<std::size_t>(he.origin)];
      const int endVertex = edges[static_cast<std::size_t>(he.next)].origin;
      const Vec3& v1 = vertices[static_cast<std::size_t>(endVertex)];
      const Vec3 d = v1 - v0;
      if (d.cross(plane.normal).dot(projected - v0) > 0.0) inside = false;
      const double t = std::clamp(d.dot(c - v0) / d.squaredNorm(), 0.0, 1.0);
      const Vec3 q = v0 + t * d;
      const double distance = (c - q).norm();
      if (distance < bestEdge) {
        bestEdge = distance;
        bestEdgePoint = q;
        bestEdgeFeature = t <= 0.0   ? PackFeature(FeatureType::Vertex, he.origin)
                          : t >= 1.0 ? PackFeature(FeatureType::Vertex, endVertex)
                                     : PackFeature(FeatureType::Edge, h >> 1);
      }
      h = he.next;
    } while (h != first);
    if (inside) {
      if (s < best.distance)
        best = {.point = projected,
                .normal = plane.normal,
                .distance = s,
                .feature = PackFeature(FeatureType::Face, f)};
    } else if (bestEdge < best.distance) {
      const Vec3 delta = c - bestEdgePoint;
      best = {.point = bestEdgePoint,
              .normal = bestEdge > kSphereDirectionEpsilon ? Vec3(delta / bestEdge) : Vec3(plane.normal),
              .distance = bestEdge,
              .feature = bestEdgeFeature};
    }
  }
  return best;
}

}  // namespace

bool CollideSphereSphere(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                         double margin, ContactManifold* out) {
  const Vec3 delta = xfA.position - xfB.position;
  const double distance = delta.norm();
  const double depth = a.Radius() + b.Radius() - distance;
  const Vec3 normal = distance > kSphereDirectionEpsilon ? Vec3(delta / distance) : Vec3::UnitY();
  out->normal = normal;
  out->depth = depth;
  out->pointCount = 0;
  if (depth < -margin) return false;
  // Midway between A's lowest point and B's highest point along the normal.
  const Vec3 surfaceA = xfA.position - a.Radius() * normal;
  const Vec3 surfaceB = xfB.position + b.Radius() * normal;
  out->normal = normal;
  out->depth = depth;
  out->pointCount = 1;
  const std::uint32_t centre = PackFeature(FeatureType::None, 0);
  out->points[0] = {
      .position = 0.5 * (surfaceA + surfaceB), .depth = depth, .featureId = MakeFeatureId(centre, centre)};
  return true;
}

bool CollideSphereBox(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                      double margin, ContactManifold* out) {
  const Vec3 centre = xfB.ApplyInverse(xfA.position);
  return Finish(ClosestOnBox(centre, b.HalfExtents()), a.Radius(), xfB, margin, out);
}

bool CollideSphereHull(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                       double margin, ContactManifold* out) {
  const Vec3 centre = xfB.ApplyInverse(xfA.position);
  return Finish(ClosestOnHull(b.GetHull(), centre), a.Radius(), xfB, margin, out);
}

}  // namespace talus
