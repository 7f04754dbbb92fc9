// Hull: an immutable convex polyhedron as a half-edge mesh (a doubly
// connected edge list, section 1 of the original write-up).
//
// The write-up keeps triangular faces to simplify the inertia tensor; Talus
// keeps true polygonal faces (coplanar triangles merged) because the SAT and
// contact clipping want them, and computes inertia exactly anyway.
//
// Memory layout: flat arrays indexed by int. Half-edges come in twin pairs
// (2e, 2e + 1), so edge e is half-edges 2e and 2e + 1. Every face's border is
// the cycle face.edge -> next -> ... counter-clockwise seen from outside, so
// the face lies on each half-edge's left. A Hull is only ever created
// validated: a closed 2-manifold (V - E + F = 2), faces planar and convex,
// adjacent faces not coplanar, every dihedral angle convex. Shapes share a
// Hull; nothing mutates it after construction.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "talus/math.h"
#include "talus/result.h"

namespace talus {

/// One directed half of an edge; the face it borders lies on its left.
struct HullHalfEdge {
  int origin = -1;  ///< vertex the half-edge starts at
  int twin = -1;    ///< the opposite half-edge (same edge, reversed)
  int next = -1;    ///< next half-edge counter-clockwise around `face`
  int prev = -1;    ///< previous half-edge around `face`
  int face = -1;    ///< face on the left
};
// Five ints, three to a cache line: the SAT's hill climbs and the clipper
// walk half-edges by index (sizes: docs/geometry-queries.md, Record sizes).
static_assert(sizeof(HullHalfEdge) == 20, "HullHalfEdge: five ints, no padding");

/// One polygonal face: an entry half-edge and its outward plane.
struct HullFace {
  int edge = -1;  ///< some half-edge on this face's border
  Plane plane;    ///< outward unit normal; every vertex is on or behind it
};
// The face queries stream every face's plane (docs/geometry-queries.md,
// Record sizes).
static_assert(sizeof(HullFace) == 40, "HullFace: entry edge (padded to 8) and a 32-byte plane");

class Hull {
 public:
  /// Builds and validates a hull from vertex positions and faces given as
  /// loops of vertex indices, counter-clockwise seen from outside.
  /// `tolerance` (metres) is how far a vertex may sit off its face's plane or
  /// in front of another face's plane; 0 picks one from the input's extent
  /// (see DefaultTolerance). Fails with a message naming the face, edge or
  /// vertex that breaks an invariant; never returns a partial hull.
  static Result<Hull> FromPolygons(std::vector<Vec3> vertices, const std::vector<std::vector<int>>& faces,
                                   double tolerance = 0.0);

  /// A box with the given half extents (metres, each > 0), centred on the
  /// origin, six quad faces.
  static Result<Hull> Box(const Vec3& halfExtents);

  /// The geometric tolerance Talus uses for a point set: a few ulps of the
  /// largest coordinate magnitudes, so it scales with position and size.
  static double DefaultTolerance(std::span<const Vec3> points);

  [[nodiscard]] std::span<const Vec3> Vertices() const { return m_vertices; }
  [[nodiscard]] std::span<const HullHalfEdge> HalfEdges() const { return m_halfEdges; }
  [[nodiscard]] std::span<const HullFace> Faces() const { return m_faces; }
  /// One outgoing half-edge per vertex (index by vertex).
  [[nodiscard]] std::span<const int> VertexEdges() const { return m_vertexEdges; }

  [[nodiscard]] int VertexCount() const { return static_cast<int>(m_vertices.size()); }
  [[nodiscard]] int HalfEdgeCount() const { return static_cast<int>(m_halfEdges.size()); }
  [[nodiscard]] int EdgeCount() const { return HalfEdgeCount() / 2; }
  [[nodiscard]] int FaceCount() const { return static_cast<int>(m_faces.size()); }

  /// Distance tolerance (metres) the hull was validated with. For a hull
  /// from BuildHull it is also the build tolerance, which may have been
  /// widened above the requested or derived one for noisy input.
  [[nodiscard]] double Tolerance() const { return m_tolerance; }

  /// The vertex indices of `face` in counter-clockwise order.
  [[nodiscard]] std::vector<int> FaceVertices(int face) const;

  /// A triangle list for drawing: each face fanned from its first vertex,
  /// counter-clockwise seen from outside.
  [[nodiscard]] std::vector<std::array<int, 3>> Triangulate() const;

 private:
  Hull() = default;

  std::vector<Vec3> m_vertices;
  std::vector<HullHalfEdge> m_halfEdges;
  std::vector<HullFace> m_faces;
  std::vector<int> m_vertexEdges;
  double m_tolerance = 0.0;
};

}  // namespace talus
