// QuickhullMesh: the mutable half-edge mesh Quickhull grows, and nothing else.
//
// It owns two index pools (half-edges and faces) with free lists, so a build
// of a million points allocates a few large arrays and never one object per
// point. Each face keeps its conflict list as a vector of (point, index)
// entries: the coordinates travel with the index, so handing orphans from
// deleted faces to new ones streams through memory instead of chasing a
// linked list across the input (this was the hottest loop in profiles). A
// freed face slot keeps a small list's capacity for reuse and releases a
// large one. Vertices are not stored:
// a half-edge's `origin` is the index of an input point, so every hull vertex
// is an input point, bit for bit.
//
// Invariants between public calls: every live face's border is a closed
// next/prev cycle of live half-edges whose `face` is that face; twins are
// mutual and lie on different live faces; each live face's plane (Newell
// normal about its centroid, offset through the centroid) is up to date; a
// point is on at most one face's conflict list, and every point on face f's
// list is more than the build tolerance in front of f's plane, with
// `farthestPoint` the one farthest in front. A point is also on at most one
// face's near list (within a band around the plane, or a vertex a merge
// removed); near points are only candidates for the builder's final
// recheck, and a point is never on a conflict and a near list at once.
//
// Face merging (MergeAcross) follows the idea of Lloyd's QuickHull3D and
// Gregorius' "Implementing Quickhull" (GDC 2014): absorb the neighbour across
// a run of shared edges, then repair the two junction vertices, which may
// have been left with only two faces around them (a redundant vertex) or may
// have turned a neighbouring triangle into a sliver that must be absorbed
// too. Points that sat on a face deleted by a merge are handed back to the
// caller as orphans, to be reassigned to the new faces.
#pragma once

#include <span>
#include <vector>

#include "talus/math.h"

namespace talus {

/// A working half-edge: `origin` is an input point index.
struct QhHalfEdge {
  int origin = -1;
  int twin = -1;
  int next = -1;
  int prev = -1;
  int face = -1;
};
// As HullHalfEdge: the horizon walk and the face merges follow half-edges
// by index (docs/geometry-quickhull.md, Record sizes).
static_assert(sizeof(QhHalfEdge) == 20, "QhHalfEdge: five ints, no padding");

/// Life cycle of a working face.
enum class QhFaceState : unsigned char {
  kAlive,    ///< on the hull
  kVisible,  ///< seen from the current eye point, about to be deleted
  kDeleted,  ///< on the free list
};

/// One outside point on a face's conflict list: a copy of its coordinates
/// and its input index.
struct QhConflict {
  Vec3 point;
  int index = -1;
};
// Two to a cache line: every new face's conflict lists are refilled from
// its predecessors' (docs/geometry-quickhull.md, Record sizes).
static_assert(sizeof(QhConflict) == 32, "QhConflict: a copied point and its index (padded to 8)");

/// A working face: its border, plane, and conflict list (outside points).
struct QhFace {
  int edge = -1;        ///< some half-edge on the border
  int vertexCount = 0;  ///< number of border half-edges
  Vec3 normal = Vec3::Zero();
  double offset = 0.0;  ///< plane: normal . x = offset
  Vec3 centroid = Vec3::Zero();
  std::vector<QhConflict> conflicts;  ///< outside points given to this face
  /// Points within the near band of this face's plane (not outside): they
  /// are rechecked once merging has moved the planes (see hull_builder.cpp).
  std::vector<QhConflict> nearPoints;
  int farthestPoint = -1;  ///< input index of the farthest conflict, -1 if none
  double farthestDistance = 0.0;
  QhFaceState state = QhFaceState::kDeleted;
  bool queued = false;  ///< already waiting in the builder's face queue
};

class QuickhullMesh {
 public:
  /// Prepares an empty mesh over `points` (which must outlive the mesh),
  /// using `tolerance` (metres) for merge decisions.
  QuickhullMesh(std::span<const Vec3> points, double tolerance);

  [[nodiscard]] std::span<const Vec3> Points() const { return m_points; }
  [[nodiscard]] double Tolerance() const { return m_tolerance; }

  [[nodiscard]] QhFace& Face(int f) { return m_faces[static_cast<std::size_t>(f)]; }
  [[nodiscard]] const QhFace& Face(int f) const { return m_faces[static_cast<std::size_t>(f)]; }
  [[nodiscard]] QhHalfEdge& Edge(int e) { return m_edges[static_cast<std::size_t>(e)]; }
  [[nodiscard]] const QhHalfEdge& Edge(int e) const { return m_edges[static_cast<std::size_t>(e)]; }
  [[nodiscard]] const Vec3& Point(int p) const { return m_points[static_cast<std::size_t>(p)]; }
  /// Size of the face pool (live and free slots); live faces have kAlive.
  [[nodiscard]] int FacePoolSize() const { return static_cast<int>(m_faces.size()); }

  /// Signed distance of point `p` from face `f`'s plane, positive in front.
  [[nodiscard]] double Distance(int f, int p) const { return Distance(f, Point(p)); }
  [[nodiscard]] double Distance(int f, const Vec3& point) const {
    const QhFace& face = Face(f);
    return face.normal.dot(point) - face.offset;
  }

  /// A new live triangle (a, b, c), counter-clockwise from outside; its
  /// half-edges are (a->b, b->c, c->a) with twins unset. Returns the face.
  int AddTriangle(int a, int b, int c);

  /// Links two half-edges as twins.
  void LinkTwins(int e0, int e1) {
    Edge(e0).twin = e1;
    Edge(e1).twin = e0;
  }

  /// Recomputes `f`'s vertex count, centroid and plane from its border.
  void UpdatePlane(int f);

  /// Frees face `f` and its half-edges (their twins are not touched).
  void DeleteFaceAndEdges(int f);

  /// Appends `conflict` to face `f`'s conflict list; `distance` is its
  /// height above the plane (must be > tolerance).
  void AddConflict(int f, const QhConflict& conflict, double distance);

  /// Appends a point near (within the band, not outside) face `f`'s plane.
  void AddNear(int f, const QhConflict& point) { Face(f).nearPoints.push_back(point); }

  /// Largest distance (metres) of one of `f`'s vertices from its plane.
  [[nodiscard]] double PlanarityError(int f) const;

  /// Moves all of `f`'s conflict and near points to the end of `out` and
  /// empties both lists.
  void TakeConflicts(int f, std::vector<QhConflict>& out);

  /// True when face `f` and the face across half-edge `e` (on f) should be
  /// one face: either centroid is not clearly behind the other's plane.
  [[nodiscard]] bool ShouldMerge(int f, int e) const;

  /// Absorbs the face across half-edge `e` (which lies on live face `f`)
  /// into `f`, repairs the junction vertices, and recomputes the planes of
  /// every face it changed. Conflict points of deleted faces are appended
  /// to `orphans`. Returns the number of hull vertices removed. When the
  /// merge would collapse the surface (see Collapsed) it stops there and
  /// the mesh must be abandoned.
  int MergeAcross(int f, int e, std::vector<QhConflict>& orphans);

  /// True once a merge found that it would leave no closed 2-manifold: the
  /// faces of a nearly flat or nearly coincident point set (flat at the
  /// build tolerance although the initial tetrahedron was not) merged until
  /// two faces share every edge, a face has fewer than three vertices, or a
  /// vertex's faces no longer form one fan. The mesh is then inconsistent
  /// and only good for being thrown away; the builder refuses or retries.
  [[nodiscard]] bool Collapsed() const { return m_collapsed; }

  /// The border of face `f` as input point indices, counter-clockwise.
  void FaceLoop(int f, std::vector<int>& loop) const;

 private:
  int AllocateEdge();
  int AllocateFace();
  void FreeEdge(int e);
  void FreeFace(int f, std::vector<QhConflict>& orphans);
  // Repairs the vertex where half-edge `in` (ending there) meets `out`
  // (leaving it), both on face `f`. Returns the number of vertices removed.
  int RepairJunction(int f, int in, std::vector<QhConflict>& orphans);
  // Records a collapse (see Collapsed) and returns 0 vertices removed.
  int MarkCollapsed();

  // No face of a build over at most INT_MAX / 8 points has more border
  // edges than this; a longer walk means a broken loop.
  static constexpr int kMaxLoopLength = 1 << 28;

  std::span<const Vec3> m_points;
  double m_tolerance;
  bool m_collapsed = false;
  std::vector<QhHalfEdge> m_edges;
  std::vector<QhFace> m_faces;
  std::vector<int> m_freeEdges;
  std::vector<int> m_freeFaces;
  std::vector<int> m_loopScratch;  // UpdatePlane's copy of a face's border (point indices)
};

}  // namespace talus
