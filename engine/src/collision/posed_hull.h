// PosedHull: a Hull placed in the world by a rotation matrix and a
// position, with the few world-space queries the SAT and the manifold
// builders need. Nothing is copied: vertices and planes are transformed on
// the fly, so a query touches only the features it visits.
//
// Support points climb the half-edge graph (hill climbing, section 1 of the
// write-up): from a start vertex, move to any neighbour that is farther
// along the direction until none is. On a convex polyhedron the local
// maximum is the global one; with a start vertex near the answer (an edge's
// own vertex for an edge axis) it takes a step or two.
#pragma once

#include <cstddef>
#include <span>

#include "talus/hull.h"
#include "talus/math.h"
#include "talus/transform.h"

namespace talus {

/// The vertex of `hull`'s graph farthest along `direction`, by hill climbing
/// from `start`, with the vertex positions read from `vertices` (the hull's
/// own, or the same vertices moved rigidly into another frame, `direction`
/// given in that frame). Moves to the first neighbour that is strictly
/// farther, so the answer depends only on the inputs.
[[nodiscard]] inline int ClimbSupport(const Hull& hull, std::span<const Vec3> vertices, const Vec3& direction,
                                      int start) {
  const auto edges = hull.HalfEdges();
  const auto vertexEdges = hull.VertexEdges();
  int v = start;
  double best = direction.dot(vertices[static_cast<std::size_t>(v)]);
  for (bool moved = true; moved;) {
    moved = false;
    const int first = vertexEdges[static_cast<std::size_t>(v)];
    int h = first;
    do {
      const HullHalfEdge& twin = edges[static_cast<std::size_t>(edges[static_cast<std::size_t>(h)].twin)];
      const double value = direction.dot(vertices[static_cast<std::size_t>(twin.origin)]);
      if (value > best) {
        best = value;
        v = twin.origin;
        moved = true;
        break;
      }
      h = twin.next;
    } while (h != first);
  }
  return v;
}

struct PosedHull {
  const Hull* hull = nullptr;
  Mat3 rotation = Mat3::Identity();  ///< local axes in world space
  Vec3 position = Vec3::Zero();      ///< metres

  static PosedHull Make(const Hull& hull, const Transform& transform) {
    return {.hull = &hull, .rotation = transform.rotation.toRotationMatrix(), .position = transform.position};
  }

  [[nodiscard]] Vec3 Vertex(int v) const {
    return rotation * hull->Vertices()[static_cast<std::size_t>(v)] + position;
  }
  [[nodiscard]] Vec3 FaceNormal(int f) const {
    return rotation * hull->Faces()[static_cast<std::size_t>(f)].plane.normal;
  }
  [[nodiscard]] Plane FacePlane(int f) const {
    const Plane& local = hull->Faces()[static_cast<std::size_t>(f)].plane;
    const Vec3 n = rotation * local.normal;
    return {.normal = n, .offset = local.offset + n.dot(position)};
  }
  /// The origin vertex of half-edge h.
  [[nodiscard]] int Origin(int h) const { return hull->HalfEdges()[static_cast<std::size_t>(h)].origin; }
  /// Edge e's start (origin of half-edge 2e) and its direction in world space.
  [[nodiscard]] int EdgeStart(int e) const { return Origin(2 * e); }
  [[nodiscard]] int EdgeEnd(int e) const { return Origin(2 * e + 1); }
  [[nodiscard]] Vec3 EdgeDirection(int e) const {
    const auto vertices = hull->Vertices();
    return rotation * (vertices[static_cast<std::size_t>(EdgeEnd(e))] -
                       vertices[static_cast<std::size_t>(EdgeStart(e))]);
  }

  /// The vertex farthest along `worldDirection`, by hill climbing from
  /// `start`. Deterministic: the result depends only on the inputs.
  [[nodiscard]] int Support(const Vec3& worldDirection, int start) const {
    return ClimbSupport(*hull, hull->Vertices(), rotation.transpose() * worldDirection, start);
  }

  /// max over vertices of worldDirection . vertex (metres for a unit
  /// direction), via Support from `start`.
  [[nodiscard]] double SupportDistance(const Vec3& worldDirection, int start) const {
    return worldDirection.dot(Vertex(Support(worldDirection, start)));
  }
};

}  // namespace talus
