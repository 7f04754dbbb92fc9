// The working half-edge mesh of Quickhull: pools, planes, conflict lists and
// face merging. See quickhull_mesh.h for the invariants.
#include "geometry/quickhull_mesh.h"

#include "geometry/polygon_normal.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace talus {
namespace {

// Largest conflict list capacity (entries) a freed face slot keeps for its
// next tenant: small lists are the common case and reusing them avoids
// allocation, while the few huge lists of the first faces would otherwise
// pin memory for the whole build.
constexpr std::size_t kKeptConflictCapacity = 256;

void ReleaseLargeList(QhFace& face) {
  if (face.conflicts.capacity() > kKeptConflictCapacity) std::vector<QhConflict>().swap(face.conflicts);
  if (face.nearPoints.capacity() > kKeptConflictCapacity) std::vector<QhConflict>().swap(face.nearPoints);
}

}  // namespace

QuickhullMesh::QuickhullMesh(std::span<const Vec3> points, double tolerance)
    : m_points(points), m_tolerance(tolerance) {
  // A hull of n vertices has at most 2n - 4 triangles and 6n - 12 half-edges;
  // reserving for a modest hull avoids regrowth in the common case.
  const std::size_t guess = std::min<std::size_t>(points.size(), 4096);
  m_edges.reserve(6 * guess + 64);
  m_faces.reserve(2 * guess + 32);
}

int QuickhullMesh::AllocateEdge() {
  if (!m_freeEdges.empty()) {
    const int e = m_freeEdges.back();
    m_freeEdges.pop_back();
    return e;
  }
  m_edges.emplace_back();
  return static_cast<int>(m_edges.size()) - 1;
}

int QuickhullMesh::AllocateFace() {
  if (!m_freeFaces.empty()) {
    const int f = m_freeFaces.back();
    m_freeFaces.pop_back();
    return f;
  }
  m_faces.emplace_back();
  return static_cast<int>(m_faces.size()) - 1;
}

void QuickhullMesh::FreeEdge(int e) {
  Edge(e).face = -1;
  m_freeEdges.push_back(e);
}

void QuickhullMesh::FreeFace(int f, std::vector<QhConflict>& orphans) {
  TakeConflicts(f, orphans);
  ReleaseLargeList(Face(f));
  // `queued` is left as it is on purpose: a queue entry may still name this
  // slot, and a face that later reuses the slot is then already queued.
  Face(f).state = QhFaceState::kDeleted;
  Face(f).edge = -1;
  m_freeFaces.push_back(f);
}

int QuickhullMesh::AddTriangle(int a, int b, int c) {
  const int f = AllocateFace();
  const int e0 = AllocateEdge();
  const int e1 = AllocateEdge();
  const int e2 = AllocateEdge();
  Edge(e0) = {.origin = a, .twin = -1, .next = e1, .prev = e2, .face = f};
  Edge(e1) = {.origin = b, .twin = -1, .next = e2, .prev = e0, .face = f};
  Edge(e2) = {.origin = c, .twin = -1, .next = e0, .prev = e1, .face = f};
  QhFace& face = Face(f);
  face.edge = e0;
  face.state = QhFaceState::kAlive;
  face.conflicts.clear();
  face.nearPoints.clear();
  face.farthestPoint = -1;
  face.farthestDistance = 0.0;
  UpdatePlane(f);
  return f;
}

void QuickhullMesh::UpdatePlane(int f) {
  QhFace& face = Face(f);
  // Centroid first, then Newell's normal about it: differences of nearby
  // points keep full precision even far from the origin.
  Vec3 centroid = Vec3::Zero();
  int count = 0;
  int e = face.edge;
  do {
    centroid += Point(Edge(e).origin);
    ++count;
    e = Edge(e).next;
  } while (e != face.edge);
  centroid /= static_cast<double>(count);
  // Accurate cross products (geometry/polygon_normal.h): thin faces keep a
  // plane that fits their vertices. The loop is walked once into a small
  // buffer so the normal sees the vertices by position.
  m_loopScratch.clear();
  e = face.edge;
  do {
    m_loopScratch.push_back(Edge(e).origin);
    e = Edge(e).next;
  } while (e != face.edge);
  Vec3 normal = PolygonNormal(
      count, [&](int i) -> const Vec3& { return Point(m_loopScratch[static_cast<std::size_t>(i)]); },
      centroid);
  const double length = ScaledNorm(normal);
  // A zero-area sliver keeps a zero normal: every distance to it is then 0,
  // which is "not clearly behind", so the merge pass absorbs it.
  if (length > 0.0) normal /= length;
  face.vertexCount = count;
  face.centroid = centroid;
  face.normal = normal;
  face.offset = normal.dot(centroid);
}

void QuickhullMesh::DeleteFaceAndEdges(int f) {
  const int start = Face(f).edge;
  int e = start;
  do {
    const int next = Edge(e).next;
    FreeEdge(e);
    e = next;
  } while (e != start);
  assert(Face(f).conflicts.empty() && Face(f).nearPoints.empty());
  ReleaseLargeList(Face(f));
  Face(f).state = QhFaceState::kDeleted;
  Face(f).edge = -1;
  m_freeFaces.push_back(f);
}

void QuickhullMesh::AddConflict(int f, const QhConflict& conflict, double distance) {
  QhFace& face = Face(f);
  face.conflicts.push_back(conflict);
  if (face.farthestPoint < 0 || distance > face.farthestDistance) {
    face.farthestPoint = conflict.index;
    face.farthestDistance = distance;
  }
}

void QuickhullMesh::TakeConflicts(int f, std::vector<QhConflict>& out) {
  QhFace& face = Face(f);
  out.insert(out.end(), face.conflicts.begin(), face.conflicts.end());
  out.insert(out.end(), face.nearPoints.begin(), face.nearPoints.end());
  face.conflicts.clear();
  face.nearPoints.clear();
  face.farthestPoint = -1;
  face.farthestDistance = 0.0;
}

double QuickhullMesh::PlanarityError(int f) const {
  double worst = 0.0;
  const int start = Face(f).edge;
  int e = start;
  do {
    worst = std::max(worst, std::abs(Distance(f, Edge(e).origin)));
    e = Edge(e).next;
  } while (e != start);
  return worst;
}

bool QuickhullMesh::ShouldMerge(int f, int e) const {
  const QhFace& a = Face(f);
  const QhFace& b = Face(Edge(Edge(e).twin).face);
  // Convex and distinct only when each centroid is clearly behind the
  // other's plane; anything else (coplanar within tolerance, or concave
  // from rounding) becomes one face.
  const double bAboveA = a.normal.dot(b.centroid) - a.offset;
  const double aAboveB = b.normal.dot(a.centroid) - b.offset;
  return bAboveA > -m_tolerance || aAboveB > -m_tolerance;
}

int QuickhullMesh::MergeAcross(int f, int e, std::vector<QhConflict>& orphans) {
  const int g = Edge(Edge(e).twin).face;
  if (g == f || Face(g).state != QhFaceState::kAlive) return MarkCollapsed();
  // The shared boundary may be a run of several edges: find its ends. When
  // it is all of f's border, f and g are the whole surface (a flat pillow).
  int start = e;
  while (Edge(Edge(Edge(start).prev).twin).face == g) {
    start = Edge(start).prev;
    if (start == e) return MarkCollapsed();
  }
  int end = e;
  while (Edge(Edge(Edge(end).next).twin).face == g) end = Edge(end).next;
  const int fBefore = Edge(start).prev;
  const int fAfter = Edge(end).next;
  const int gAfter = Edge(Edge(start).twin).next;
  const int gBefore = Edge(Edge(end).twin).prev;
  // g lying wholly inside f's border would leave nothing of g to join.
  if (gAfter == Edge(end).twin || Edge(gAfter).face != g) return MarkCollapsed();

  // g's remaining border joins f's.
  for (int h = gAfter;; h = Edge(h).next) {
    Edge(h).face = f;
    if (h == gBefore) break;
  }
  int removed = -1;  // a run of k edges removes its k - 1 inner vertices
  for (int h = start;;) {
    const int next = Edge(h).next;
    // A vertex inside the run leaves the hull; it may end up slightly in
    // front of the merged plane, so it is kept for the near-point recheck.
    if (h != start) AddNear(f, {Point(Edge(h).origin), Edge(h).origin});
    FreeEdge(Edge(h).twin);
    FreeEdge(h);
    ++removed;
    if (h == end) break;
    h = next;
  }
  Edge(fBefore).next = gAfter;
  Edge(gAfter).prev = fBefore;
  Edge(gBefore).next = fAfter;
  Edge(fAfter).prev = gBefore;
  Face(f).edge = fBefore;
  FreeFace(g, orphans);

  // A junction vertex left with the same neighbour on both sides has only
  // two faces around it: remove it (repeat until none is left). Each repair
  // removes a vertex of f, so this ends; a face left with fewer than three
  // vertices means the surface collapsed.
  bool repaired = true;
  while (repaired && !m_collapsed) {
    repaired = false;
    int h = Face(f).edge;
    int count = 0;
    do {
      const int n = Edge(h).next;
      if (++count > kMaxLoopLength || Edge(n).next == h) return MarkCollapsed();
      if (Edge(Edge(h).twin).face == Edge(Edge(n).twin).face) {
        removed += RepairJunction(f, h, orphans);
        repaired = true;
        break;
      }
      h = n;
    } while (h != Face(f).edge);
  }
  if (m_collapsed) return removed;
  UpdatePlane(f);
  return removed;
}

int QuickhullMesh::MarkCollapsed() {
  m_collapsed = true;
  return 0;
}

int QuickhullMesh::RepairJunction(int f, int in, std::vector<QhConflict>& orphans) {
  // f runs u -in-> v -out-> w; the neighbour h runs w -tout-> v -tin-> u.
  const int out = Edge(in).next;
  const int tin = Edge(in).twin;
  const int tout = Edge(out).twin;
  const int h = Edge(tin).face;
  // On a 2-manifold h runs w -> v -> u; anything else is a collapse.
  if (Edge(tout).next != tin) return MarkCollapsed();
  const int v = Edge(out).origin;
  AddNear(f, {Point(v), v});  // v leaves the hull: recheck it later
  if (Face(h).vertexCount == 3) {
    // h would shrink to two edges: absorb it. Its third edge x (u -> w)
    // hands its twin to f's shortened edge.
    // When x's twin is on f too, f and h are the whole surface.
    const int x = Edge(tin).next;
    if (Edge(x).next != tout || Edge(Edge(x).twin).face == f) return MarkCollapsed();
    const int after = Edge(out).next;
    Edge(in).next = after;
    Edge(after).prev = in;
    LinkTwins(in, Edge(x).twin);
    FreeEdge(out);
    FreeEdge(tin);
    FreeEdge(tout);
    FreeEdge(x);
    FreeFace(h, orphans);
  } else {
    // Drop v from both faces: in becomes u -> w, tout becomes w -> u.
    const int fAfter = Edge(out).next;
    Edge(in).next = fAfter;
    Edge(fAfter).prev = in;
    const int hAfter = Edge(tin).next;
    Edge(tout).next = hAfter;
    Edge(hAfter).prev = tout;
    LinkTwins(in, tout);
    FreeEdge(out);
    FreeEdge(tin);
    Face(h).edge = tout;
    UpdatePlane(h);
  }
  Face(f).edge = in;
  return 1;
}

void QuickhullMesh::FaceLoop(int f, std::vector<int>& loop) const {
  loop.clear();
  const int start = Face(f).edge;
  int e = start;
  do {
    loop.push_back(Edge(e).origin);
    e = Edge(e).next;
  } while (e != start);
}

}  // namespace talus
