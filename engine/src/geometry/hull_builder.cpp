// Quickhull in 3D (section 1 of the original write-up; Barber, Dobkin and
// Huhdanpaa 1996 for the algorithm, Lloyd's QuickHull3D and Gregorius'
// "Implementing Quickhull", GDC 2014, for the robust practice).
//
// The idea: a point that is extreme in some direction is on the hull, and a
// point inside the current hull never will be. Start from a tetrahedron of
// extreme points and give every outside point to one face it is in front of
// (that face's conflict list). Then, while some face has outside points,
// take its farthest one (the eye), find the faces it sees by a depth-first
// walk across twins from that face (the walk's boundary, in order, is the
// horizon), replace the visible faces by a cone of triangles from the eye to
// the horizon, merge each new triangle with any neighbour it is not clearly
// convex against (so coplanar points give one polygonal face and rounding
// never leaves a concave edge), and hand the orphaned points of the deleted
// faces to the new face they are farthest in front of, dropping those now
// inside. Every decision uses one distance tolerance derived from the
// input's extent, and the same tolerance is what Hull::FromPolygons checks.
//
// Merges move planes, so points kept near a face (and vertices a merge
// removed) are rechecked against the final planes and processed again when
// they ended up in front; when that does not settle, or a merged face is
// not planar within the tolerance, the build is repeated with a wider
// tolerance (qhull's remedy too: it widens its reported precision).
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "geometry/hull_build_trace.h"
#include "geometry/polygon_normal.h"
#include "geometry/quickhull_mesh.h"
#include "talus/hull_builder.h"

namespace talus {
namespace {

std::string Metres(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.3g m", value);
  return buffer;
}

// Largest coordinate magnitude (metres) the builder accepts. It forms
// squared distances and cross products of coordinate differences (up to
// 2 x 1e150, so squares up to 12 x 1e300 = 1.2e301) and Newell sums of
// millions of those: all stay below the double limit of 1.8e308 with a
// factor ~1e7 to spare. Lengths beyond it are no physical body anyway; the
// refusal says why instead of a misleading "collinear" from an overflow.
constexpr double kMaxCoordinate = 1e150;

// Smallest extent (metres, largest side of the bounding box) the builder can
// resolve: squares of differences down to 1e-14 of it (1e-308) must stay
// normal doubles, not underflow to zero (below 1e-140 a set would be
// refused as "coincident" although its points are distinct).
constexpr double kMinExtent = 1e-140;

std::string Number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.3g", value);
  return buffer;
}

// Rejects NaN, infinite and too large coordinates, naming the first bad
// point, and a set too small to measure.
std::optional<Error> CheckCoordinates(std::span<const Vec3> points) {
  static constexpr std::array<const char*, 3> kAxis = {"x", "y", "z"};
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const double value = points[i][axis];
      if (std::isnan(value)) {
        return Error{"point " + std::to_string(i) + ": coordinate " + kAxis[static_cast<std::size_t>(axis)] +
                     " is NaN"};
      }
      if (std::isinf(value)) {
        return Error{"point " + std::to_string(i) + ": coordinate " + kAxis[static_cast<std::size_t>(axis)] +
                     " is infinite"};
      }
      if (std::abs(value) > kMaxCoordinate) {
        return Error{"point " + std::to_string(i) + ": coordinate " + kAxis[static_cast<std::size_t>(axis)] +
                     " = " + Number(value) + " m exceeds the limit of " + Number(kMaxCoordinate) +
                     " m in magnitude, beyond which squared distances between points overflow a double"};
      }
    }
  }
  Vec3 lowest = points[0];
  Vec3 highest = points[0];
  for (const Vec3& p : points) {
    lowest = lowest.cwiseMin(p);
    highest = highest.cwiseMax(p);
  }
  const double extent = (highest - lowest).maxCoeff();
  if (extent > 0.0 && extent < kMinExtent) {
    return Error{"the points span only " + Metres(extent) + ", below the smallest extent of " +
                 Metres(kMinExtent) +
                 " at which squared distances between points stay above the double range"};
  }
  return std::nullopt;
}

// The first tetrahedron: the two farthest apart of the six axis-extreme
// points, the point farthest from their line, and the point farthest from
// the plane of those three. Each step doubles as the degeneracy test.
Result<std::array<int, 4>> FindInitialSimplex(std::span<const Vec3> points, double tolerance) {
  std::array<int, 6> extremes{};
  for (int axis = 0; axis < 3; ++axis) {
    int lo = 0;
    int hi = 0;
    for (std::size_t i = 1; i < points.size(); ++i) {
      if (points[i][axis] < points[static_cast<std::size_t>(lo)][axis]) lo = static_cast<int>(i);
      if (points[i][axis] > points[static_cast<std::size_t>(hi)][axis]) hi = static_cast<int>(i);
    }
    extremes[static_cast<std::size_t>(2 * axis)] = lo;
    extremes[static_cast<std::size_t>(2 * axis + 1)] = hi;
  }
  auto at = [&](int i) -> const Vec3& { return points[static_cast<std::size_t>(i)]; };
  int i0 = extremes[0];
  int i1 = extremes[1];
  double best = -1.0;
  for (int a : extremes) {
    for (int b : extremes) {
      const double d = (at(a) - at(b)).squaredNorm();
      if (d > best) {
        best = d;
        i0 = a;
        i1 = b;
      }
    }
  }
  if (std::sqrt(best) <= tolerance) {
    return Error{"all " + std::to_string(points.size()) + " points coincide within the tolerance " +
                 Metres(tolerance) + ": they span no volume"};
  }

  const Vec3 direction = (at(i1) - at(i0)).normalized();
  int i2 = -1;
  best = -1.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double d = (points[i] - at(i0)).cross(direction).squaredNorm();
    if (d > best) {
      best = d;
      i2 = static_cast<int>(i);
    }
  }
  if (std::sqrt(best) <= tolerance) {
    return Error{"all points are collinear within the tolerance " + Metres(tolerance) +
                 " (or there are fewer than 3 distinct points): they span no volume"};
  }

  const Vec3 cross = (at(i1) - at(i0)).cross(at(i2) - at(i0));
  const Vec3 normal = cross / ScaledNorm(cross);
  int i3 = -1;
  best = -1.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double d = std::abs(normal.dot(points[i] - at(i0)));
    if (d > best) {
      best = d;
      i3 = static_cast<int>(i);
    }
  }
  if (best <= tolerance) {
    return Error{"all points are coplanar within the tolerance " + Metres(tolerance) +
                 " (or there are fewer than 4 distinct points): they span no volume"};
  }
  return std::array<int, 4>{i0, i1, i2, i3};
}

// Near band (in tolerances): points assigned less than this far below their
// best face are kept on its near list for the final recheck. Merged planes
// move by at most a few tolerances, so a point deeper than 8 can never end
// up in front; a wider band only costs memory on flat inputs.
constexpr double kNearBand = 8.0;

// Rounds of "process the queue, recheck near points" before a build is
// declared unsettled (each round normally turns far fewer points; two are
// the rule, the rest is a guard against cycling).
constexpr int kMaxRecheckRounds = 8;

// Tolerance widening for noisy input (see BuildHull): factor per attempt and
// number of attempts (4^16 ~ 4e9, from a derived 1e-15 m to ~4e-6 m).
constexpr double kWidening = 4.0;
constexpr int kMaxWidenings = 16;

// A point may become the eye this many times (a merge can remove a vertex
// that a later recheck finds in front again); a point that keeps coming
// back marks the build as unsettled, and BuildHull widens the tolerance.
constexpr unsigned char kMaxEyeVisits = 3;

// How one build at one tolerance ended.
enum class BuildStatus {
  kSettled,    // every point is inside or within the tolerance of the hull
  kUnsettled,  // points kept coming back in front after merges moved planes
  kCollapsed,  // merges or a horizon left no closed 2-manifold (see
               // QuickhullMesh::Collapsed): the set is flat at this tolerance
};

// Working state of one build: the mesh plus scratch buffers reused by every
// iteration, so the loop allocates nothing once they have grown.
class Builder {
 public:
  Builder(std::span<const Vec3> points, double tolerance, int maxVertices)
      : m_mesh(points, tolerance), m_tolerance(tolerance), m_maxVertices(maxVertices) {}

  // Builds the hull: kSettled, or why the mesh must be thrown away.
  BuildStatus Run(const std::array<int, 4>& simplex);
  [[nodiscard]] double PlanarityError() const;
  void SetTrace(HullBuildTrace* trace) { m_trace = trace; }
  [[nodiscard]] Result<Hull> Bake() const;

 private:
  void BuildTetrahedron(const std::array<int, 4>& simplex);
  void AssignToBestFace(std::span<const QhConflict> candidates, std::span<const int> faces, int skip);
  int RecheckNearPoints();
  BuildStatus ProcessQueue();
  void ComputeHorizon(int face, int eye);
  [[nodiscard]] bool HorizonIsOneLoop();
  bool AddPoint(int face, int eye);
  void Enqueue(int face);

  QuickhullMesh m_mesh;
  double m_tolerance;
  int m_maxVertices;
  int m_vertexCount = 0;
  HullBuildTrace* m_trace = nullptr;  // optional record of every iteration

  std::vector<int> m_queue;  // faces waiting to be processed, first in first out
  std::size_t m_queueHead = 0;
  std::vector<int> m_visible;
  std::vector<int> m_horizon;
  std::vector<std::array<int, 3>> m_stack;  // (face, stop edge, current edge)
  std::vector<int> m_newFaces;
  std::vector<int> m_neighbours;  // RecheckNearPoints' face and its neighbours
  std::vector<QhConflict> m_orphans;
  std::vector<unsigned char> m_eyeVisits;  // per point: times it was the eye
  std::vector<int> m_stamp;                // per point, for counting removed vertices
  int m_stampValue = 0;
  std::vector<int> m_horizonMark;  // per point, HorizonIsOneLoop's visit stamp
  int m_loopStamp = 0;
};

void Builder::BuildTetrahedron(const std::array<int, 4>& s) {
  // Orient the base so that the apex is behind it.
  int a = s[0];
  int b = s[1];
  const int c = s[2];
  const int d = s[3];
  // The triple product through a unit normal: a plain one is a product of
  // three lengths, which overflows or underflows at the extreme scales the
  // builder accepts (1e150 m coordinates, 1e-140 m sets).
  const Vec3& pa = m_mesh.Point(a);
  const Vec3 cross = AccurateCross(m_mesh.Point(b) - pa, m_mesh.Point(c) - pa);
  if ((cross / ScaledNorm(cross)).dot(m_mesh.Point(d) - pa) > 0.0) std::swap(a, b);
  const int base = m_mesh.AddTriangle(a, b, c);
  const int fBad = m_mesh.AddTriangle(b, a, d);
  const int fCbd = m_mesh.AddTriangle(c, b, d);
  const int fAcd = m_mesh.AddTriangle(a, c, d);
  auto edge = [&](int f, int k) {
    int e = m_mesh.Face(f).edge;
    for (int i = 0; i < k; ++i) e = m_mesh.Edge(e).next;
    return e;
  };
  m_mesh.LinkTwins(edge(base, 0), edge(fBad, 0));  // a-b
  m_mesh.LinkTwins(edge(base, 1), edge(fCbd, 0));  // b-c
  m_mesh.LinkTwins(edge(base, 2), edge(fAcd, 0));  // c-a
  m_mesh.LinkTwins(edge(fBad, 1), edge(fAcd, 2));  // a-d
  m_mesh.LinkTwins(edge(fBad, 2), edge(fCbd, 1));  // d-b
  m_mesh.LinkTwins(edge(fCbd, 2), edge(fAcd, 1));  // d-c
  m_vertexCount = 4;
  m_newFaces = {base, fBad, fCbd, fAcd};
}

// Gives each candidate point to the face it is farthest in front of. A point
// more than the tolerance in front goes on that face's conflict list; one
// within the near band (kNearBand tolerances) below to one tolerance above
// goes on its near list, to be rechecked after merges have moved the planes;
// a point deeper inside can never come out again and is dropped.
void Builder::AssignToBestFace(std::span<const QhConflict> candidates, std::span<const int> faces, int skip) {
  const double nearFloor = -kNearBand * m_tolerance;
  for (const QhConflict& p : candidates) {
    if (p.index == skip) continue;
    int bestFace = -1;
    double bestDistance = nearFloor;
    for (int f : faces) {
      if (m_mesh.Face(f).state != QhFaceState::kAlive) continue;
      const double d = m_mesh.Distance(f, p.point);
      if (d > bestDistance) {
        bestDistance = d;
        bestFace = f;
      }
    }
    if (bestFace < 0) continue;
    if (bestDistance > m_tolerance) {
      m_mesh.AddConflict(bestFace, p, bestDistance);
    } else {
      m_mesh.AddNear(bestFace, p);
    }
  }
}

// Merges move face planes by up to a few tolerances, so a point that was
// within the tolerance of a face when it was assigned may end up in front of
// the final face or of a neighbour. This sweep rechecks every near point
// against its face and that face's neighbours and turns those now more than
// the tolerance in front into conflict points again (qhull handles its
// "coplanar points" the same way). Returns how many were turned.
int Builder::RecheckNearPoints() {
  int turned = 0;
  for (int f = 0; f < m_mesh.FacePoolSize(); ++f) {
    if (m_mesh.Face(f).state != QhFaceState::kAlive || m_mesh.Face(f).nearPoints.empty()) continue;
    m_neighbours.clear();
    m_neighbours.push_back(f);
    const int start = m_mesh.Face(f).edge;
    int e = start;
    do {
      m_neighbours.push_back(m_mesh.Edge(m_mesh.Edge(e).twin).face);
      e = m_mesh.Edge(e).next;
    } while (e != start);
    std::vector<QhConflict>& nearPoints = m_mesh.Face(f).nearPoints;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < nearPoints.size(); ++i) {
      const QhConflict p = nearPoints[i];
      int bestFace = -1;
      double bestDistance = m_tolerance;
      for (int g : m_neighbours) {
        const double d = m_mesh.Distance(g, p.point);
        if (d > bestDistance) {
          bestDistance = d;
          bestFace = g;
        }
      }
      if (bestFace < 0) {
        nearPoints[kept++] = p;
      } else {
        m_mesh.AddConflict(bestFace, p, bestDistance);
        Enqueue(bestFace);
        ++turned;
      }
    }
    m_mesh.Face(f).nearPoints.resize(kept);
  }
  return turned;
}

// The largest distance of a face's vertex from that face's plane, over the
// whole hull: merges bounded by the tolerance keep it below the tolerance on
// clean input; noisy input can push it above (see BuildHull).
double Builder::PlanarityError() const {
  double worst = 0.0;
  for (int f = 0; f < m_mesh.FacePoolSize(); ++f) {
    if (m_mesh.Face(f).state == QhFaceState::kAlive) worst = std::max(worst, m_mesh.PlanarityError(f));
  }
  return worst;
}

void Builder::Enqueue(int face) {
  QhFace& f = m_mesh.Face(face);
  if (f.queued || f.conflicts.empty()) return;
  f.queued = true;
  m_queue.push_back(face);
}

BuildStatus Builder::Run(const std::array<int, 4>& simplex) {
  BuildTetrahedron(simplex);
  const auto pointCount = static_cast<int>(m_mesh.Points().size());
  std::vector<QhConflict> all(static_cast<std::size_t>(pointCount));
  for (int i = 0; i < pointCount; ++i) all[static_cast<std::size_t>(i)] = {m_mesh.Point(i), i};
  for (int corner : simplex) all[static_cast<std::size_t>(corner)].index = -1;
  std::erase_if(all, [](const QhConflict& c) { return c.index < 0; });
  AssignToBestFace(all, m_newFaces, -1);
  for (int f : m_newFaces) Enqueue(f);
  if (m_maxVertices > 0) m_stamp.assign(static_cast<std::size_t>(pointCount), 0);

  // Process the queue; then recheck the near points against the final
  // planes, and go on while that turns some of them into outside points.
  m_eyeVisits.assign(static_cast<std::size_t>(pointCount), 0);
  m_horizonMark.assign(static_cast<std::size_t>(pointCount), 0);
  for (int round = 0; round < kMaxRecheckRounds; ++round) {
    const BuildStatus status = ProcessQueue();
    if (status != BuildStatus::kSettled) return status;
    if (m_maxVertices > 0 && m_vertexCount >= m_maxVertices) return BuildStatus::kSettled;
    if (RecheckNearPoints() == 0) return BuildStatus::kSettled;
  }
  return BuildStatus::kUnsettled;
}

// Adds eye points until no face has conflicts; kUnsettled when a point
// keeps coming back as the eye (the build does not settle at this
// tolerance), kCollapsed when adding a point broke the surface. Each point
// is the eye at most kMaxEyeVisits times, so this ends.
BuildStatus Builder::ProcessQueue() {
  while (m_queueHead < m_queue.size()) {
    const int face = m_queue[m_queueHead++];
    // Keep the queue compact: drop the consumed prefix now and then.
    if (m_queueHead > 4096 && 2 * m_queueHead > m_queue.size()) {
      m_queue.erase(m_queue.begin(), m_queue.begin() + static_cast<std::ptrdiff_t>(m_queueHead));
      m_queueHead = 0;
    }
    QhFace& f = m_mesh.Face(face);
    f.queued = false;
    if (f.state != QhFaceState::kAlive || f.conflicts.empty()) continue;
    if (m_maxVertices > 0 && m_vertexCount >= m_maxVertices) break;
    if (++m_eyeVisits[static_cast<std::size_t>(f.farthestPoint)] > kMaxEyeVisits)
      return BuildStatus::kUnsettled;
    if (!AddPoint(face, f.farthestPoint)) return BuildStatus::kCollapsed;
  }
  return BuildStatus::kSettled;
}

// Depth-first walk over the faces the eye sees, starting at `face` and
// crossing each edge to its twin. Entering a face through an edge and
// walking its border from the edge after it lists the horizon edges (those
// whose twin's face is not visible) counter-clockwise around the visible
// region. An explicit stack keeps deep walks off the call stack.
void Builder::ComputeHorizon(int face, int eye) {
  m_visible.clear();
  m_horizon.clear();
  m_stack.clear();
  m_mesh.Face(face).state = QhFaceState::kVisible;
  m_visible.push_back(face);
  const int first = m_mesh.Face(face).edge;
  m_stack.push_back({face, first, first});
  bool atRoot = true;
  while (!m_stack.empty()) {
    auto& top = m_stack.back();
    const int e = top[2];
    if (e == top[1] && !atRoot) {
      m_stack.pop_back();
      continue;
    }
    atRoot = false;
    top[2] = m_mesh.Edge(e).next;
    const int twin = m_mesh.Edge(e).twin;
    const int neighbour = m_mesh.Edge(twin).face;
    if (m_mesh.Face(neighbour).state == QhFaceState::kVisible) continue;
    if (m_mesh.Distance(neighbour, eye) > m_tolerance) {
      m_mesh.Face(neighbour).state = QhFaceState::kVisible;
      m_visible.push_back(neighbour);
      const int start = m_mesh.Edge(twin).next;
      m_stack.push_back({neighbour, twin, start});  // stop on coming back to the entry edge
    } else {
      m_horizon.push_back(e);
    }
  }
}

// The cone can only replace a visible region that is a disk: its horizon
// must be one closed loop through distinct vertices. With exact arithmetic
// it always is; with a tolerance, a nearly flat set can make the eye "see"
// faces that ring an unseen one, or touch at a single vertex. Checked
// before anything is changed, so the caller can abandon the build cleanly.
bool Builder::HorizonIsOneLoop() {
  const std::size_t n = m_horizon.size();
  if (n < 3) return false;
  ++m_loopStamp;
  for (std::size_t i = 0; i < n; ++i) {
    const int end = m_mesh.Edge(m_mesh.Edge(m_horizon[i]).next).origin;
    if (end != m_mesh.Edge(m_horizon[(i + 1) % n]).origin) return false;
    int& mark = m_horizonMark[static_cast<std::size_t>(end)];
    if (mark == m_loopStamp) return false;  // the loop passes a vertex twice
    mark = m_loopStamp;
  }
  return true;
}

// Adds `eye` to the hull; false when the surface collapsed (the mesh must
// then be abandoned: see BuildStatus::kCollapsed).
bool Builder::AddPoint(int face, int eye) {
  ComputeHorizon(face, eye);
  if (!HorizonIsOneLoop()) return false;
  if (m_trace != nullptr) RecordHullBuildStep(*m_trace, m_mesh, eye, m_horizon);

  if (m_maxVertices > 0) {
    // Vertices of visible faces that are not on the horizon leave the hull.
    ++m_stampValue;
    for (int e : m_horizon) m_stamp[static_cast<std::size_t>(m_mesh.Edge(e).origin)] = m_stampValue;
    for (int v : m_visible) {
      const int start = m_mesh.Face(v).edge;
      int e = start;
      do {
        auto& mark = m_stamp[static_cast<std::size_t>(m_mesh.Edge(e).origin)];
        if (mark != m_stampValue) {
          mark = m_stampValue;
          --m_vertexCount;
        }
        e = m_mesh.Edge(e).next;
      } while (e != start);
    }
    ++m_vertexCount;
  }

  // The horizon as (origin, hidden twin) pairs, before the edges are freed.
  m_orphans.clear();
  for (int v : m_visible) m_mesh.TakeConflicts(v, m_orphans);
  for (int& e : m_horizon) e = m_mesh.Edge(e).twin;  // now the hidden side's half-edge
  for (int v : m_visible) m_mesh.DeleteFaceAndEdges(v);

  // The cone: one triangle per horizon edge, hidden twin -> (b, a) becomes
  // (a, b, eye) on the new side; neighbours share the eye's side edges.
  m_newFaces.clear();
  for (int hidden : m_horizon) {
    const int b = m_mesh.Edge(hidden).origin;
    const int a = m_mesh.Edge(m_mesh.Edge(hidden).next).origin;
    const int nf = m_mesh.AddTriangle(a, b, eye);
    m_mesh.LinkTwins(m_mesh.Face(nf).edge, hidden);
    m_newFaces.push_back(nf);
  }
  const std::size_t n = m_newFaces.size();
  for (std::size_t i = 0; i < n; ++i) {
    assert(m_mesh.Edge(m_horizon[i]).origin == m_mesh.Edge(m_mesh.Edge(m_horizon[(i + 1) % n]).next).origin);
    const int here = m_mesh.Face(m_newFaces[i]).edge;
    const int there = m_mesh.Face(m_newFaces[(i + 1) % n]).edge;
    m_mesh.LinkTwins(m_mesh.Edge(here).next, m_mesh.Edge(there).prev);  // b -> eye with eye -> b
  }

  // Merge each new face with every neighbour it is not clearly convex to.
  for (int nf : m_newFaces) {
    bool merged = true;
    while (merged && m_mesh.Face(nf).state == QhFaceState::kAlive) {
      merged = false;
      const int start = m_mesh.Face(nf).edge;
      int e = start;
      do {
        if (m_mesh.ShouldMerge(nf, e)) {
          m_vertexCount -= m_mesh.MergeAcross(nf, e, m_orphans);
          if (m_mesh.Collapsed()) return false;
          merged = true;
          break;
        }
        e = m_mesh.Edge(e).next;
      } while (e != start);
    }
  }

  AssignToBestFace(m_orphans, m_newFaces, eye);
  for (int nf : m_newFaces) {
    if (m_mesh.Face(nf).state == QhFaceState::kAlive) Enqueue(nf);
  }
  return true;
}

Result<Hull> Builder::Bake() const {
  // Vertices numbered by first appearance walking the face pool in order:
  // deterministic, and independent of how the input was laid out in memory.
  std::vector<int> vertexOf(m_mesh.Points().size(), -1);
  std::vector<Vec3> vertices;
  std::vector<std::vector<int>> faces;
  std::vector<int> loop;
  for (int f = 0; f < m_mesh.FacePoolSize(); ++f) {
    if (m_mesh.Face(f).state != QhFaceState::kAlive) continue;
    m_mesh.FaceLoop(f, loop);
    for (int& p : loop) {
      int& v = vertexOf[static_cast<std::size_t>(p)];
      if (v < 0) {
        v = static_cast<int>(vertices.size());
        vertices.push_back(m_mesh.Point(p));
      }
      p = v;
    }
    faces.push_back(loop);
  }
  auto hull = Hull::FromPolygons(std::move(vertices), faces, m_tolerance);
  if (!hull) return Error{"its hull failed validation: " + hull.GetError().message};
  return hull;
}

// Largest points x faces product for which BuildHull checks every input
// point against every face of the finished hull (about 20 ms): the build
// only rechecks points near the faces they were given to, and a point
// dropped as inside can, on nearly degenerate sets, end up slightly in
// front of a face that merges moved. Bigger inputs skip this safety net.
constexpr double kFullCheckBudget = 2e7;

// The first input point more than the tolerance in front of a face of
// `hull`, as a message, when the input is small enough to check them all.
std::optional<std::string> FindPointInFront(const Hull& hull, std::span<const Vec3> points) {
  if (static_cast<double>(points.size()) * hull.FaceCount() > kFullCheckBudget) return std::nullopt;
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int f = 0; f < hull.FaceCount(); ++f) {
      const double distance = hull.Faces()[static_cast<std::size_t>(f)].plane.SignedDistance(points[i]);
      if (distance > hull.Tolerance()) {
        return "point " + std::to_string(i) + " is " + Metres(distance) + " in front of face " +
               std::to_string(f);
      }
    }
  }
  return std::nullopt;
}

}  // namespace

Result<Hull> BuildHull(std::span<const Vec3> points, const HullBuildSettings& settings) {
  if (settings.maxVertices != 0 && settings.maxVertices < 4) {
    return Error{"HullBuildSettings::maxVertices must be 0 (no cap) or at least 4, got " +
                 std::to_string(settings.maxVertices)};
  }
  if (!std::isfinite(settings.tolerance) || settings.tolerance < 0.0) {
    return Error{"HullBuildSettings::tolerance must be finite and >= 0, got " +
                 std::to_string(settings.tolerance)};
  }
  if (points.size() < 4) {
    return Error{"a convex hull needs at least 4 points, got " + std::to_string(points.size())};
  }
  if (points.size() > static_cast<std::size_t>(std::numeric_limits<int>::max() / 8)) {
    return Error{"too many points for a hull: " + std::to_string(points.size())};
  }
  if (auto error = CheckCoordinates(points)) return *error;
  // A requested tolerance below the derived one is below the rounding of a
  // plane distance at these coordinates: no build can honour it (a grid-
  // snapped sphere asked for 1e-20 m collapsed and was refused as flat at
  // 0.6 m), so it starts at the derived one.
  double tolerance = std::max(settings.tolerance, Hull::DefaultTolerance(points));
  // Noisy input (points nearly coplanar at a scale well above the
  // tolerance, or differences of far-from-origin coordinates that carry
  // rounding noise the derived tolerance cannot know about) can leave a
  // merged face with a vertex off its plane or a point in front that no
  // recheck settles. Then the whole build is repeated with the tolerance
  // widened to kWidening x the larger of the tolerance and the measured
  // planarity error, for building and validation alike; the hull's
  // Tolerance() reports the one it was built and validated with.
  // A mesh that collapsed (a set flat or coincident at this tolerance,
  // though its first tetrahedron was not) is retried wider as well: either
  // a wider tolerance merges the set cleanly, or the initial tetrahedron
  // test refuses it as flat. The loop runs at most kMaxWidenings + 1 builds,
  // each of which ends (QuickhullMesh::Collapsed, kMaxEyeVisits).
  const double startTolerance = tolerance;
  std::string lastProblem;
  for (int attempt = 0; attempt <= kMaxWidenings; ++attempt) {
    auto simplex = FindInitialSimplex(points, tolerance);
    if (!simplex) {
      if (attempt == 0) return simplex.GetError();
      return Error{simplex.GetError().message + " (the tolerance was widened from " + Metres(startTolerance) +
                   " after the build at " + Metres(tolerance / kWidening) + " failed: " + lastProblem + ")"};
    }
    Builder builder(points, tolerance, settings.maxVertices);
    // A widened retry records afresh: the trace shows the build that counted.
    if (settings.trace != nullptr) settings.trace->steps.clear();
    builder.SetTrace(settings.trace);
    const BuildStatus status = builder.Run(simplex.Value());
    double planarity = 0.0;
    if (status == BuildStatus::kCollapsed) {
      lastProblem = "merging coplanar faces collapsed the surface";
    } else {
      planarity = builder.PlanarityError();
      if (status == BuildStatus::kUnsettled) {
        lastProblem = "points kept reappearing in front of merged faces";
      } else if (planarity > tolerance) {
        lastProblem = "a merged face is " + Metres(planarity) + " off its plane";
      } else {
        auto hull = builder.Bake();
        if (hull) {
          // A vertex cap leaves points outside on purpose.
          std::optional<std::string> outside;
          if (settings.maxVertices == 0) outside = FindPointInFront(hull.Value(), points);
          if (!outside) return hull;
          lastProblem = *outside;
        } else {
          lastProblem = hull.GetError().message;
        }
      }
    }
    tolerance = kWidening * std::max(tolerance, planarity);
  }
  return Error{"no valid hull: the build did not settle with the tolerance widened " +
               std::to_string(kMaxWidenings) + " times from " + Metres(startTolerance) + " to " +
               Metres(tolerance / kWidening) + "; last problem: " + lastProblem +
               " (please keep this point set as a regression case)"};
}

}  // namespace talus
