// Geometric queries on a baked Hull: support vertex by hill climbing,
// containment, ray cast, plane classification and bounding volumes.
//
// Every query reads the immutable Hull only and allocates nothing except
// TightBoundingSphere (one index permutation). Results depend only on the
// hull and the arguments: no hidden state, no time- or address-based seeds.
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include "talus/hull_queries.h"
#include "talus/mass_properties.h"

namespace talus {

// Hill climbing over the half-edge graph (section 1 of the write-up): from
// the current vertex, look at every neighbour (circulate the outgoing
// half-edges with twin -> next) and move to the best one that is strictly
// farther along `direction`. Strict improvement makes the walk terminate
// (the support value rises every move and there are finitely many
// vertices), so a plateau of tied vertices simply stops it. It is also
// exact: at a vertex of a convex polyhedron the outgoing edges span the
// cone of directions into the solid, so if any vertex lies farther along
// `direction`, some outgoing edge climbs; a vertex with no climbing edge is
// a global maximum (ties aside).
int SupportVertex(const Hull& hull, const Vec3& direction, int startVertex) {
  assert(startVertex >= 0 && startVertex < hull.VertexCount());
  const auto vertices = hull.Vertices();
  const auto edges = hull.HalfEdges();
  const auto vertexEdges = hull.VertexEdges();
  int current = startVertex;
  double best = direction.dot(vertices[static_cast<std::size_t>(current)]);
  for (;;) {
    int next = current;
    const int first = vertexEdges[static_cast<std::size_t>(current)];
    int h = first;
    do {
      const HullHalfEdge& out = edges[static_cast<std::size_t>(h)];
      const int neighbour = edges[static_cast<std::size_t>(out.twin)].origin;
      const double value = direction.dot(vertices[static_cast<std::size_t>(neighbour)]);
      if (value > best) {
        best = value;
        next = neighbour;
      }
      h = edges[static_cast<std::size_t>(out.twin)].next;
    } while (h != first);
    if (next == current) return current;
    current = next;
  }
}

int SupportVertexBruteForce(const Hull& hull, const Vec3& direction) {
  const auto vertices = hull.Vertices();
  int best = 0;
  double bestValue = direction.dot(vertices[0]);
  for (int v = 1; v < hull.VertexCount(); ++v) {
    const double value = direction.dot(vertices[static_cast<std::size_t>(v)]);
    if (value > bestValue) {
      bestValue = value;
      best = v;
    }
  }
  return best;
}

// A convex solid is the intersection of its faces' back half-spaces.
bool ContainsPoint(const Hull& hull, const Vec3& point, double tolerance) {
  assert(tolerance >= 0.0);
  for (const HullFace& face : hull.Faces()) {
    if (!(face.plane.SignedDistance(point) <= tolerance)) return false;
  }
  return true;
}

// Cyrus-Beck clipping of the ray against every face's half-space (the 3D
// slab test): a face the ray runs towards (n . d < 0) gives an entering
// parameter, one it runs away from an exiting parameter. The ray is inside
// the solid for max(entering) <= t <= min(exiting). A ray parallel to a
// face misses when its origin is in front of it. The hit is the latest
// entry, reported only when it is at t >= 0: an origin inside the hull has
// every entry behind it and so never enters.
std::optional<RayHit> RayCast(const Hull& hull, const Vec3& origin, const Vec3& direction,
                              double maxDistance) {
  const double length = direction.norm();
  assert(length > 0.0);
  if (!(length > 0.0) || !std::isfinite(length) || !origin.allFinite()) return std::nullopt;
  const Vec3 unit = direction / length;
  double enter = -std::numeric_limits<double>::infinity();
  double exit = maxDistance;
  int enterFace = -1;
  for (int f = 0; f < hull.FaceCount(); ++f) {
    const Plane& plane = hull.Faces()[static_cast<std::size_t>(f)].plane;
    const double distance = plane.SignedDistance(origin);
    const double approach = plane.normal.dot(unit);
    if (approach == 0.0) {
      if (distance > 0.0) return std::nullopt;
      continue;
    }
    const double t = -distance / approach;
    if (approach < 0.0) {
      if (t > enter) {
        enter = t;
        enterFace = f;
      }
    } else {
      exit = std::min(exit, t);
    }
    if (enter > exit) return std::nullopt;
  }
  if (enterFace < 0 || enter < 0.0) return std::nullopt;
  return RayHit{.distance = enter,
                .normal = hull.Faces()[static_cast<std::size_t>(enterFace)].plane.normal,
                .face = enterFace};
}

// The hull's extent along the plane normal is [n . lowest, n . highest],
// with both ends found by hill climbing rather than a full vertex scan.
PlaneSide ClassifyPlane(const Hull& hull, const Plane& plane, double tolerance) {
  assert(tolerance >= 0.0);
  const auto vertices = hull.Vertices();
  const int highest = SupportVertex(hull, plane.normal);
  const int lowest = SupportVertex(hull, -plane.normal, highest);
  if (plane.SignedDistance(vertices[static_cast<std::size_t>(lowest)]) > tolerance) return PlaneSide::Front;
  if (plane.SignedDistance(vertices[static_cast<std::size_t>(highest)]) < -tolerance) return PlaneSide::Back;
  return PlaneSide::Crossing;
}

namespace {

// Radius that reaches every vertex from `center` (the largest distance).
double EnclosingRadius(const Hull& hull, const Vec3& center) {
  double squared = 0.0;
  for (const Vec3& v : hull.Vertices()) squared = std::max(squared, (v - center).squaredNorm());
  return std::sqrt(squared);
}

}  // namespace

Sphere CentroidBoundingSphere(const Hull& hull) {
  // Density 1 is always valid, so the Result cannot hold an error.
  const Vec3 centroid = ComputeMassProperties(hull, 1.0).Value().centerOfMass;
  return {.center = centroid, .radius = EnclosingRadius(hull, centroid)};
}

namespace {

// Relative slack of the "is outside the current sphere" test in Welzl's
// loops: points within 1e-13 of the hull's size of the surface count as
// inside, so round-off in a freshly computed circumsphere cannot make its
// own defining points look outside and trigger pointless rebuilds. The
// final radius is recomputed exactly, so the slack never loses a vertex.
constexpr double kSphereSlack = 1e-13;

// Largest |sin|^2 of the angle between two edges (or scaled volume of three)
// below which a circumcircle (circumsphere) is treated as degenerate: the
// points are collinear (coplanar) to within 1e-10 rad, and the exact
// circumcentre would be dominated by round-off.
constexpr double kDegenerateSine2 = 1e-20;

struct Ball {
  Vec3 center = Vec3::Zero();
  double radius = 0.0;
};

Ball DiametralBall(const Vec3& a, const Vec3& b) {
  return {.center = 0.5 * (a + b), .radius = 0.5 * (b - a).norm()};
}

bool Covers(const Ball& ball, const Vec3& p, double slack) {
  return (p - ball.center).norm() <= ball.radius + slack;
}

// The smallest ball with a, b, c on its boundary: their circumcircle.
// Collinear points fall back to the ball over the farthest pair, which
// covers the middle one.
Ball CircumBall(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 u = b - a;
  const Vec3 v = c - a;
  const Vec3 w = u.cross(v);
  const double w2 = w.squaredNorm();
  if (w2 <= kDegenerateSine2 * u.squaredNorm() * v.squaredNorm()) {
    Ball best = DiametralBall(a, b);
    for (const Ball& other : {DiametralBall(a, c), DiametralBall(b, c)}) {
      if (other.radius > best.radius) best = other;
    }
    return best;
  }
  const Vec3 offset = (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u)) / (2.0 * w2);
  return {.center = a + offset, .radius = offset.norm()};
}

// The ball with a, b, c, d on its boundary: their circumsphere. Coplanar
// points fall back to the smallest ball over a pair or triple that covers
// all four.
Ball CircumBall(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double slack) {
  const Vec3 u = b - a;
  const Vec3 v = c - a;
  const Vec3 w = d - a;
  const double det = u.dot(v.cross(w));
  if (det * det <= kDegenerateSine2 * u.squaredNorm() * v.squaredNorm() * w.squaredNorm()) {
    const std::array<Vec3, 4> p = {a, b, c, d};
    Ball best{.center = a, .radius = std::numeric_limits<double>::infinity()};
    const auto consider = [&](const Ball& ball) {
      if (ball.radius >= best.radius) return;
      for (const Vec3& q : p) {
        if (!Covers(ball, q, slack)) return;
      }
      best = ball;
    };
    for (std::size_t i = 0; i < 4; ++i) {
      for (std::size_t j = i + 1; j < 4; ++j) {
        consider(DiametralBall(p[i], p[j]));
        for (std::size_t k = j + 1; k < 4; ++k) consider(CircumBall(p[i], p[j], p[k]));
      }
    }
    return best;
  }
  const Vec3 offset =
      (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) /
      (2.0 * det);
  return {.center = a + offset, .radius = offset.norm()};
}

// SplitMix64 (Steele, Lea and Flood 2014): a tiny, fully specified generator,
// so the shuffle below is the same on every standard library.
std::uint64_t SplitMix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Fixed seed of the deterministic shuffle; any constant works.
constexpr std::uint64_t kShuffleSeed = 0x5EED0F7A1u;

}  // namespace

// Welzl's minimum enclosing ball ("Smallest enclosing disks (balls and
// ellipsoids)", 1991) in its iterative form: visit the points in a shuffled
// order; when point i is outside the current ball, the new ball must have i
// on its boundary, so rebuild it from the earlier points with i fixed, and
// recurse the same way for a second, third and fourth fixed boundary point.
// A random order gives expected linear time; the order here is a
// Fisher-Yates shuffle with a fixed seed, so the answer is reproducible.
// Finally the radius is recomputed as the exact farthest vertex distance
// from the centre, and the centroid sphere is returned if it is smaller
// (which only round-off on a degenerate input could cause).
Sphere TightBoundingSphere(const Hull& hull) {
  const auto vertices = hull.Vertices();
  std::vector<Vec3> p(vertices.begin(), vertices.end());
  std::uint64_t state = kShuffleSeed;
  for (std::size_t i = p.size() - 1; i > 0; --i) {
    std::swap(p[i], p[SplitMix64(state) % (i + 1)]);
  }
  const Aabb box = ComputeAabb(hull);
  const double slack = kSphereSlack * (box.max - box.min).norm();

  Ball ball{.center = p[0], .radius = 0.0};
  for (std::size_t i = 1; i < p.size(); ++i) {
    if (Covers(ball, p[i], slack)) continue;
    ball = {.center = p[i], .radius = 0.0};
    for (std::size_t j = 0; j < i; ++j) {
      if (Covers(ball, p[j], slack)) continue;
      ball = DiametralBall(p[i], p[j]);
      for (std::size_t k = 0; k < j; ++k) {
        if (Covers(ball, p[k], slack)) continue;
        ball = CircumBall(p[i], p[j], p[k]);
        for (std::size_t l = 0; l < k; ++l) {
          if (Covers(ball, p[l], slack)) continue;
          ball = CircumBall(p[i], p[j], p[k], p[l], slack);
        }
      }
    }
  }
  const Sphere tight{.center = ball.center, .radius = EnclosingRadius(hull, ball.center)};
  const Sphere centroid = CentroidBoundingSphere(hull);
  return tight.radius <= centroid.radius ? tight : centroid;
}

Aabb ComputeAabb(const Hull& hull) {
  Aabb box{.min = hull.Vertices()[0], .max = hull.Vertices()[0]};
  for (const Vec3& v : hull.Vertices()) {
    box.min = box.min.cwiseMin(v);
    box.max = box.max.cwiseMax(v);
  }
  return box;
}

}  // namespace talus
