// Baking and validating the flat half-edge Hull.
//
// FromPolygons is the single door through which every Hull comes into
// being, Quickhull's output included, so the invariants documented in
// talus/hull.h are checked in one place. All checks are O(E) apart from a
// per-face planarity pass, so validating even a million-vertex hull is cheap
// next to building it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include "talus/hull.h"

#include "geometry/polygon_normal.h"

namespace talus {
namespace {

std::string FaceName(std::size_t face) { return "face " + std::to_string(face); }

// Newell's method: the area-weighted normal of a polygon, robust for
// slightly non-planar loops. Its length is twice the polygon's area. Taken
// about the loop's centroid: cross products of raw coordinates lose the
// normal's direction to cancellation when the face is small next to its
// distance from the origin (a 0.1 m face at 1e4 m would be off by 1e-6 rad).
// The cross products are accurate ones (geometry/polygon_normal.h), or a
// long thin face gets a plane that misses its own vertices.
Vec3 NewellNormal(const std::vector<Vec3>& vertices, const std::vector<int>& loop) {
  Vec3 centroid = Vec3::Zero();
  for (int v : loop) centroid += vertices[static_cast<std::size_t>(v)];
  centroid /= static_cast<double>(loop.size());
  return PolygonNormal(
      static_cast<int>(loop.size()),
      [&](int i) -> const Vec3& {
        return vertices[static_cast<std::size_t>(loop[static_cast<std::size_t>(i)])];
      },
      centroid);
}

std::optional<Error> CheckFaceLoops(const std::vector<Vec3>& vertices,
                                    const std::vector<std::vector<int>>& faces) {
  const int vertexCount = static_cast<int>(vertices.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& loop = faces[f];
    if (loop.size() < 3) {
      return Error{FaceName(f) + " has " + std::to_string(loop.size()) + " vertices (needs at least 3)"};
    }
    for (std::size_t i = 0; i < loop.size(); ++i) {
      if (loop[i] < 0 || loop[i] >= vertexCount) {
        return Error{FaceName(f) + " refers to vertex " + std::to_string(loop[i]) + ", but there are only " +
                     std::to_string(vertexCount)};
      }
      for (std::size_t j = 0; j < i; ++j) {
        if (loop[j] == loop[i]) {
          return Error{FaceName(f) + " visits vertex " + std::to_string(loop[i]) + " twice"};
        }
      }
    }
  }
  return std::nullopt;
}

// The inputs FromPolygons can reject before building anything: finite
// vertices, a usable tolerance, enough vertices and faces, and face loops
// of distinct, existing vertices.
std::optional<Error> CheckInputs(const std::vector<Vec3>& vertices,
                                 const std::vector<std::vector<int>>& faces, double tolerance) {
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    if (!vertices[v].allFinite()) return Error{"vertex " + std::to_string(v) + " is not finite"};
  }
  if (!std::isfinite(tolerance) || tolerance < 0.0) {
    return Error{"tolerance must be finite and >= 0, got " + std::to_string(tolerance)};
  }
  if (vertices.size() < 4 || faces.size() < 4) {
    return Error{"a closed polyhedron needs at least 4 vertices and 4 faces, got " +
                 std::to_string(vertices.size()) + " and " + std::to_string(faces.size())};
  }
  return CheckFaceLoops(vertices, faces);
}

// Directed edges in face order, each linked to its neighbours around its
// face; twins are still unknown (-1).
std::vector<HullHalfEdge> LinkFaceLoops(const std::vector<std::vector<int>>& faces) {
  std::vector<HullHalfEdge> loose;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& loop = faces[f];
    const int first = static_cast<int>(loose.size());
    const int count = static_cast<int>(loop.size());
    for (int i = 0; i < count; ++i) {
      loose.push_back({.origin = loop[static_cast<std::size_t>(i)],
                       .twin = -1,
                       .next = first + (i + 1) % count,
                       .prev = first + (i + count - 1) % count,
                       .face = static_cast<int>(f)});
    }
  }
  return loose;
}

// Twins through the half-edges bucketed by origin (a counting sort, so no
// hashing and no per-edge allocation): the twin of from->to is the edge
// among `to`'s few outgoing ones that leads back to `from`. Fails on an
// edge used twice in one direction or one without a twin.
std::optional<Error> MatchTwins(std::size_t vertexCount, std::vector<HullHalfEdge>& loose) {
  std::vector<int> bucketStart(vertexCount + 1, 0);
  for (const auto& h : loose) ++bucketStart[static_cast<std::size_t>(h.origin) + 1];
  for (std::size_t v = 0; v < vertexCount; ++v) bucketStart[v + 1] += bucketStart[v];
  std::vector<int> byOrigin(loose.size());
  {
    std::vector<int> fill(bucketStart.begin(), bucketStart.end() - 1);
    for (std::size_t i = 0; i < loose.size(); ++i) {
      byOrigin[static_cast<std::size_t>(fill[static_cast<std::size_t>(loose[i].origin)]++)] =
          static_cast<int>(i);
    }
  }
  auto destination = [&](const HullHalfEdge& h) { return loose[static_cast<std::size_t>(h.next)].origin; };
  for (auto& h : loose) {
    const int to = destination(h);
    int sameDirection = 0;
    for (int k = bucketStart[static_cast<std::size_t>(h.origin)];
         k < bucketStart[static_cast<std::size_t>(h.origin) + 1]; ++k) {
      if (destination(loose[static_cast<std::size_t>(byOrigin[static_cast<std::size_t>(k)])]) == to)
        ++sameDirection;
    }
    if (sameDirection > 1) {
      return Error{"edge " + std::to_string(h.origin) + "->" + std::to_string(to) +
                   " is used twice in the same direction (" + FaceName(static_cast<std::size_t>(h.face)) +
                   "): faces are not consistently oriented, or the surface is not a 2-manifold"};
    }
    for (int k = bucketStart[static_cast<std::size_t>(to)]; k < bucketStart[static_cast<std::size_t>(to) + 1];
         ++k) {
      const int candidate = byOrigin[static_cast<std::size_t>(k)];
      if (destination(loose[static_cast<std::size_t>(candidate)]) == h.origin) h.twin = candidate;
    }
    if (h.twin < 0) {
      return Error{"edge " + std::to_string(h.origin) + "->" + std::to_string(to) + " of " +
                   FaceName(static_cast<std::size_t>(h.face)) + " has no twin: the surface is not closed"};
    }
  }
  return std::nullopt;
}

// Renumbers so that twins are (2e, 2e + 1): edge e is then one index.
std::vector<HullHalfEdge> PairTwins(const std::vector<HullHalfEdge>& loose) {
  std::vector<int> newIndex(loose.size(), -1);
  int nextIndex = 0;
  for (std::size_t i = 0; i < loose.size(); ++i) {
    if (newIndex[i] >= 0) continue;
    newIndex[i] = nextIndex++;
    newIndex[static_cast<std::size_t>(loose[i].twin)] = nextIndex++;
  }
  std::vector<HullHalfEdge> halfEdges(loose.size());
  for (std::size_t i = 0; i < loose.size(); ++i) {
    const HullHalfEdge& h = loose[i];
    halfEdges[static_cast<std::size_t>(newIndex[i])] = {.origin = h.origin,
                                                        .twin = newIndex[static_cast<std::size_t>(h.twin)],
                                                        .next = newIndex[static_cast<std::size_t>(h.next)],
                                                        .prev = newIndex[static_cast<std::size_t>(h.prev)],
                                                        .face = h.face};
  }
  return halfEdges;
}

// One outgoing half-edge per vertex into `vertexEdges`. Every vertex must
// be used, and its outgoing half-edges must form a single fan (a manifold
// vertex, not two cones touching at a point).
std::optional<Error> LinkVertexFans(std::size_t vertexCount, const std::vector<HullHalfEdge>& halfEdges,
                                    std::vector<int>& vertexEdges) {
  std::vector<int> outDegree(vertexCount, 0);
  vertexEdges.assign(vertexCount, -1);
  for (std::size_t i = 0; i < halfEdges.size(); ++i) {
    const auto origin = static_cast<std::size_t>(halfEdges[i].origin);
    ++outDegree[origin];
    if (vertexEdges[origin] < 0) vertexEdges[origin] = static_cast<int>(i);
  }
  for (std::size_t v = 0; v < vertexCount; ++v) {
    if (outDegree[v] == 0) return Error{"vertex " + std::to_string(v) + " is not used by any face"};
    int fan = 0;
    int h = vertexEdges[v];
    do {
      h = halfEdges[static_cast<std::size_t>(halfEdges[static_cast<std::size_t>(h)].twin)].next;
      ++fan;
    } while (h != vertexEdges[v] && fan <= outDegree[v]);
    if (fan != outDegree[v]) {
      return Error{"vertex " + std::to_string(v) +
                   " is not a manifold vertex (its faces form more than one fan)"};
    }
  }
  return std::nullopt;
}

// Face f's plane (Newell), after checking that its polygon is planar within
// `tolerance`, convex, and winds once counter-clockwise around the normal.
Result<Plane> FacePlane(const std::vector<Vec3>& vertices, const std::vector<int>& loop, std::size_t f,
                        double tolerance) {
  const Vec3 newell = NewellNormal(vertices, loop);
  const double twiceArea = ScaledNorm(newell);
  if (!(twiceArea > 0.0)) return Error{FaceName(f) + " has zero area"};
  const Vec3 normal = newell / twiceArea;
  double offset = 0.0;
  for (int v : loop) offset += normal.dot(vertices[static_cast<std::size_t>(v)]);
  offset /= static_cast<double>(loop.size());
  double turning = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec3& a = vertices[static_cast<std::size_t>(loop[i])];
    const Vec3& b = vertices[static_cast<std::size_t>(loop[(i + 1) % loop.size()])];
    const Vec3& c = vertices[static_cast<std::size_t>(loop[(i + 2) % loop.size()])];
    if (std::abs(normal.dot(a) - offset) > tolerance) {
      char distance[64];
      std::snprintf(distance, sizeof(distance), "%.3g m off its plane (tolerance %.3g m)",
                    std::abs(normal.dot(a) - offset), tolerance);
      return Error{FaceName(f) + " is not planar: vertex " + std::to_string(loop[i]) + " is " + distance};
    }
    // c must not lie right of the directed line a -> b (seen from outside).
    const Vec3 ab = b - a;
    const Vec3 inwardDirection = normal.cross(ab);
    const Vec3 inward = inwardDirection / ScaledNorm(inwardDirection);
    if (inward.dot(c - a) < -tolerance) {
      return Error{FaceName(f) + " is not convex at vertex " + std::to_string(loop[(i + 1) % loop.size()])};
    }
    // The turning angle between the edges projected into the plane: a
    // face off its plane by up to the tolerance (a large fraction of a
    // tiny face's size) turns by 2 pi exactly only in projection.
    const Vec3 abInPlane = ab - normal * normal.dot(ab);
    const Vec3 bc = c - b;
    const Vec3 bcInPlane = bc - normal * normal.dot(bc);
    turning += std::atan2(normal.dot(abInPlane.cross(bcInPlane)), abInPlane.dot(bcInPlane));
  }
  // Local left turns everywhere still allow a loop that winds twice.
  if (std::abs(turning - 2.0 * std::numbers::pi) > 1e-6) {
    return Error{FaceName(f) + " winds " + std::to_string(turning / (2.0 * std::numbers::pi)) +
                 " times around its normal (must be once, counter-clockwise from outside)"};
  }
  return Plane{.normal = normal, .offset = offset};
}

// Dihedral angles: across every edge, the neighbour face's vertices next
// to the edge must lie behind this face's plane (convex), and the two
// faces must not be the same plane (those should have been one polygon).
std::optional<Error> CheckDihedralAngles(const std::vector<Vec3>& vertices,
                                         const std::vector<HullHalfEdge>& halfEdges,
                                         const std::vector<HullFace>& faces, double tolerance) {
  for (std::size_t h = 0; h < halfEdges.size(); ++h) {
    const HullHalfEdge& edge = halfEdges[h];
    const HullHalfEdge& twin = halfEdges[static_cast<std::size_t>(edge.twin)];
    const Plane& plane = faces[static_cast<std::size_t>(edge.face)].plane;
    const int after = halfEdges[static_cast<std::size_t>(twin.next)].next;
    const int before = twin.prev;
    double highest = -std::numeric_limits<double>::infinity();
    for (int probe : {after, before}) {
      const int v = halfEdges[static_cast<std::size_t>(probe)].origin;
      highest = std::max(highest, plane.SignedDistance(vertices[static_cast<std::size_t>(v)]));
    }
    if (highest > tolerance) {
      return Error{"faces " + std::to_string(edge.face) + " and " + std::to_string(twin.face) +
                   " meet at a concave edge"};
    }
    if (highest >= -tolerance) {
      // Both probes are on the plane: check the whole neighbour face.
      double lowest = 0.0;
      int h2 = twin.next;
      do {
        const int v = halfEdges[static_cast<std::size_t>(h2)].origin;
        lowest = std::min(lowest, plane.SignedDistance(vertices[static_cast<std::size_t>(v)]));
        h2 = halfEdges[static_cast<std::size_t>(h2)].next;
      } while (h2 != twin.next);
      if (lowest >= -tolerance) {
        return Error{"faces " + std::to_string(edge.face) + " and " + std::to_string(twin.face) +
                     " are coplanar (they should be one face)"};
      }
    }
  }
  return std::nullopt;
}

}  // namespace

double Hull::DefaultTolerance(std::span<const Vec3> points) {
  // The classic Quickhull choice: a few ulps of the summed largest
  // magnitudes per axis. Far from the origin the representable spacing grows,
  // and so must the tolerance.
  Vec3 maxAbs = Vec3::Zero();
  for (const Vec3& p : points) maxAbs = maxAbs.cwiseMax(p.cwiseAbs());
  constexpr double kUlps = 3.0;
  return kUlps * std::numeric_limits<double>::epsilon() * maxAbs.sum();
}

// The steps in the order their failures are reported: the input, the
// half-edge links and twins, the vertex fans, Euler's formula, each face's
// plane, the dihedral angles.
Result<Hull> Hull::FromPolygons(std::vector<Vec3> vertices, const std::vector<std::vector<int>>& faces,
                                double tolerance) {
  if (auto error = CheckInputs(vertices, faces, tolerance)) return *error;
  if (tolerance == 0.0) tolerance = DefaultTolerance(vertices);

  Hull hull;
  hull.m_tolerance = tolerance;
  std::vector<HullHalfEdge> loose = LinkFaceLoops(faces);
  if (auto error = MatchTwins(vertices.size(), loose)) return *error;
  hull.m_halfEdges = PairTwins(loose);
  const std::size_t vertexCount = vertices.size();
  if (auto error = LinkVertexFans(vertexCount, hull.m_halfEdges, hull.m_vertexEdges)) return *error;

  const long euler = static_cast<long>(vertexCount) - static_cast<long>(hull.m_halfEdges.size() / 2) +
                     static_cast<long>(faces.size());
  if (euler != 2) {
    return Error{"V - E + F = " + std::to_string(euler) + ", not 2: the surface is not a sphere"};
  }

  hull.m_faces.resize(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    Result<Plane> plane = FacePlane(vertices, faces[f], f, tolerance);
    if (!plane) return plane.GetError();
    hull.m_faces[f].plane = plane.Value();
  }
  for (std::size_t h = 0; h < hull.m_halfEdges.size(); ++h) {
    hull.m_faces[static_cast<std::size_t>(hull.m_halfEdges[h].face)].edge = static_cast<int>(h);
  }
  if (auto error = CheckDihedralAngles(vertices, hull.m_halfEdges, hull.m_faces, tolerance)) return *error;

  hull.m_vertices = std::move(vertices);
  return hull;
}

Result<Hull> Hull::Box(const Vec3& halfExtents) {
  if (!halfExtents.allFinite() || (halfExtents.array() <= 0.0).any()) {
    return Error{"box half extents must be finite and > 0"};
  }
  const Vec3& e = halfExtents;
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) {
    corners.emplace_back((i & 1) ? e.x() : -e.x(), (i & 2) ? e.y() : -e.y(), (i & 4) ? e.z() : -e.z());
  }
  // Counter-clockwise from outside; corner bit 0 = +x, bit 1 = +y, bit 2 = +z.
  const std::vector<std::vector<int>> faces = {
      {1, 3, 7, 5}, {0, 4, 6, 2},  // +x, -x
      {2, 6, 7, 3}, {0, 1, 5, 4},  // +y, -y
      {4, 5, 7, 6}, {0, 2, 3, 1},  // +z, -z
  };
  return FromPolygons(std::move(corners), faces);
}

std::vector<int> Hull::FaceVertices(int face) const {
  std::vector<int> loop;
  const int start = m_faces[static_cast<std::size_t>(face)].edge;
  int h = start;
  do {
    loop.push_back(m_halfEdges[static_cast<std::size_t>(h)].origin);
    h = m_halfEdges[static_cast<std::size_t>(h)].next;
  } while (h != start);
  return loop;
}

std::vector<std::array<int, 3>> Hull::Triangulate() const {
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(m_halfEdges.size() - 2 * m_faces.size());
  for (int f = 0; f < FaceCount(); ++f) {
    const std::vector<int> loop = FaceVertices(f);
    for (std::size_t i = 1; i + 1 < loop.size(); ++i) triangles.push_back({loop[0], loop[i], loop[i + 1]});
  }
  return triangles;
}

}  // namespace talus
