// The Separating Axis Test: face queries, edge queries (all pairs or Gauss
// map pruned), the cached-axis probe and the choice of the contact axis.
//
// The search runs in A's body frame (SatFrame): B's vertices and planes are
// moved there once per query, A's are read as stored.
// - a face of A with plane (n, d): separation = min over B of n.b - d;
// - a face of B likewise with the roles swapped;
// - Full mode, an edge pair: n = eA x eB normalised, both polyhedra
//   projected on n by hill climbing from the edges' own vertices,
//   separation = the larger of the two one-sided gaps (the write-up);
// - GaussMapPruned, an edge pair that builds a Minkowski face: the edges are
//   the supports, so separation = n . (pB - pA) with n oriented away from A;
//   a pair that would become the best is confirmed by projection (round-off
//   on a sliver's tiny edge can pass a pair whose edges are not supports).
// The minimum overlap over all E^2 edge axes equals the minimum over the
// Minkowski-face pairs (the overlap along a direction is the support
// distance of A - B, smallest at one of its faces), which is why pruning
// loses nothing (Gregorius, GDC 2013). The two modes therefore agree on the
// verdict and on the least overlap up to round-off; the axis they finally
// report is measured by one world-space function, EvaluateSatAxis, so the
// same axis gives bit-identical numbers in both.
#include "collision/sat.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "collision/narrow_phase_scratch.h"

namespace talus {
namespace {

constexpr double kNegativeInfinity = -std::numeric_limits<double>::infinity();

struct FaceQuery {
  int face = -1;
  double separation = kNegativeInfinity;
};

struct EdgeQuery {
  int edgeA = -1;
  int edgeB = -1;
  double separation = kNegativeInfinity;
};

// max over `vertices` of n . v, by scanning them all: exact on any hull,
// where hill climbing can stop at a vertex that is a local maximum only
// through round-off (a sliver's faces fitted within its tolerance).
double HighestAlong(std::span<const Vec3> vertices, const Vec3& n) {
  double high = kNegativeInfinity;
  for (const Vec3& v : vertices) high = std::max(high, n.dot(v));
  return high;
}

// min over `vertices` of n . v (see HighestAlong).
double LowestAlong(std::span<const Vec3> vertices, const Vec3& n) { return -HighestAlong(vertices, -n); }

// max over p's vertices of n . vertex in world space, by scanning them all:
// exact on any hull, where hill climbing (PosedHull::Support) can stop at a
// vertex that is a local maximum only through round-off (a sliver's edge
// of 1e-13 m whose direction is round-off, its far end exactly level with
// the start along n). A climb can only stop short, so its figure is a lower
// bound of this one; the two are bit-identical whenever the climb reaches
// the top (the same expression on the same vertex).
double ProjectedSupport(const PosedHull& p, const Vec3& n) {
  double high = kNegativeInfinity;
  for (int v = 0; v < p.hull->VertexCount(); ++v) high = std::max(high, n.dot(p.Vertex(v)));
  return high;
}

// The vertex farthest along `direction`: the hill climb from `start`, unless
// some vertex lies strictly farther (the climb stalled at a round-off local
// maximum), then the first such farthest vertex. Ties keep the climb's
// answer, so a well-shaped hull gets the vertex it always got.
int ProjectedSupportVertex(const PosedHull& p, const Vec3& direction, int start) {
  int best = p.Support(direction, start);
  double high = direction.dot(p.Vertex(best));
  for (int v = 0; v < p.hull->VertexCount(); ++v) {
    const double value = direction.dot(p.Vertex(v));
    if (value > high) {
      high = value;
      best = v;
    }
  }
  return best;
}

// Separation of face f of `p` against `q` in world space: how far q's
// deepest vertex is in front of the face plane, every vertex of q projected.
double FaceSeparation(const PosedHull& p, int f, const PosedHull& q) {
  const Plane plane = p.FacePlane(f);
  return -ProjectedSupport(q, -plane.normal) - plane.offset;
}

// The face of one hull whose plane the other hull, `q` with its vertices
// `qVertices` in the same frame as the planes, is farthest in front of;
// stops at the first one beyond `margin`. The support hint carries over
// from face to face.
template <typename PlaneOf>
FaceQuery QueryFaces(int faceCount, PlaneOf planeOf, const Hull& q, std::span<const Vec3> qVertices,
                     double margin, NarrowPhaseStats* stats) {
  FaceQuery best;
  int start = 0;
  int tested = 0;
  for (int f = 0; f < faceCount; ++f) {
    ++tested;
    const Plane& plane = planeOf(f);
    start = ClimbSupport(q, qVertices, -plane.normal, start);
    double separation = plane.normal.dot(qVertices[static_cast<std::size_t>(start)]) - plane.offset;
    // The climb can stop short of q's deepest vertex (a round-off local
    // maximum on a sliver), so its separation is an upper bound: enough to
    // discard a face, not to keep one. A face that would become the best is
    // measured by projecting every vertex of q (equal to the climb's figure,
    // bit for bit, when the climb reached the bottom).
    if (!(separation > best.separation)) continue;
    separation = std::min(separation, -HighestAlong(qVertices, -plane.normal) - plane.offset);
    if (separation > best.separation) {
      best = {.face = f, .separation = separation};
      if (separation > margin) break;
    }
  }
  if (stats) stats->faceAxesTested += static_cast<std::uint64_t>(tested);
  return best;
}

// How EdgeSeparation finds each hull's extent along the axis.
enum class Extent : std::uint8_t {
  // Hill climbing from the edges' own vertices: a step or two, but it can
  // stop short on a sliver, so the gap is an upper bound of the true one
  // (each extent can only come out too small). Discards pairs.
  Climbed,
  // Every vertex projected: the true gap. Measures a pair that is kept.
  Projected,
};

// The projection gap along the cross product of edges ea (of a) and eb (of
// b), in world space; `axis` gets the direction from A towards B that
// achieves it. The write-up's measure, valid for any edge pair. With
// Extent::Climbed the figure is an upper bound of the Projected one (equal
// whenever every climb reaches its hull's top).
double EdgeSeparation(const PosedHull& a, int ea, const Vec3& dirA, const PosedHull& b, int eb,
                      const Vec3& dirB, Extent extent, Vec3* axis) {
  const Vec3 cross = dirA.cross(dirB);
  const double crossSquared = cross.squaredNorm();
  if (crossSquared <= kParallelEdgeSine * kParallelEdgeSine * dirA.squaredNorm() * dirB.squaredNorm()) {
    return kNegativeInfinity;
  }
  const Vec3 n = cross / std::sqrt(crossSquared);
  const int startA = a.EdgeStart(ea);
  const int startB = b.EdgeStart(eb);
  const bool climb = extent == Extent::Climbed;
  const double highA = climb ? a.SupportDistance(n, startA) : ProjectedSupport(a, n);
  const double lowA = climb ? -a.SupportDistance(-n, startA) : -ProjectedSupport(a, -n);
  const double highB = climb ? b.SupportDistance(n, startB) : ProjectedSupport(b, n);
  const double lowB = climb ? -b.SupportDistance(-n, startB) : -ProjectedSupport(b, -n);
  const double alongPlus = lowB - highA;   // B beyond A along +n
  const double alongMinus = lowA - highB;  // B beyond A along -n
  if (alongMinus > alongPlus) {
    *axis = -n;
    return alongMinus;
  }
  *axis = n;
  return alongPlus;
}

// Full mode: every edge pair (the write-up), discarded by its climbed gap
// (an upper bound) and, when that would beat the best so far, measured by
// projecting every vertex. Measured by the climb alone, a sliver's pair
// whose climb stalled on a round-off-flat edge 1.5e-13 m long read a gap
// 2.5e-4 m too large and beat every correct axis, so the reported overlap
// was 1.7e-4 m less than the least overlap of any axis (fuzz finding
// full_mode_edge_climb_stalled_on_sliver_reported_too_shallow).
EdgeQuery QueryAllEdges(const PosedHull& a, const PosedHull& b, double margin, NarrowPhaseStats* stats) {
  EdgeQuery best;
  std::uint64_t tested = 0;
  const int edgeCountA = a.hull->EdgeCount();
  const int edgeCountB = b.hull->EdgeCount();
  for (int ea = 0; ea < edgeCountA; ++ea) {
    const Vec3 dirA = a.EdgeDirection(ea);
    for (int eb = 0; eb < edgeCountB; ++eb) {
      ++tested;
      Vec3 axis = Vec3::Zero();
      const Vec3 dirB = b.EdgeDirection(eb);
      double separation = EdgeSeparation(a, ea, dirA, b, eb, dirB, Extent::Climbed, &axis);
      if (!(separation > best.separation)) continue;
      separation = EdgeSeparation(a, ea, dirA, b, eb, dirB, Extent::Projected, &axis);
      if (separation > best.separation) {
        best = {.edgeA = ea, .edgeB = eb, .separation = separation};
        if (separation > margin) {
          if (stats) stats->edgeAxesTested += tested;
          return best;  // early out on the first separating axis
        }
      }
    }
  }
  if (stats) stats->edgeAxesTested += tested;
  return best;
}

// One edge of A as the Minkowski edge query reads it against every edge of
// B: its faces' normals, a vertex and direction, and the bisector of its
// arc on the Gauss map (the side an axis n must lie on).
struct MinkowskiEdgeA {
  Vec3 normalLeft;
  Vec3 normalRight;
  Vec3 point;
  Vec3 dir;
  double dirSquared = 0.0;
  Vec3 bisector;
};

MinkowskiEdgeA DescribeEdgeOfA(const SatFrame& frame, std::size_t ea) {
  const auto verticesA = frame.hullA->Vertices();
  const auto halfEdgesA = frame.hullA->HalfEdges();
  const SatFrame::Arc& arcA = frame.arcsA[ea];
  MinkowskiEdgeA edge;
  edge.normalLeft = frame.hullA->Faces()[static_cast<std::size_t>(arcA.left)].plane.normal;
  edge.normalRight = frame.hullA->Faces()[static_cast<std::size_t>(arcA.right)].plane.normal;
  edge.point = verticesA[static_cast<std::size_t>(halfEdgesA[2 * ea].origin)];
  edge.dir = verticesA[static_cast<std::size_t>(halfEdgesA[2 * ea + 1].origin)] - edge.point;
  edge.dirSquared = edge.dir.squaredNorm();
  // The side of A's arc that n must lie on. n = eA x eB is perpendicular
  // to eA, so it lies in the plane of A's two face normals; its sign is
  // chosen against the arc's bisector, built in that plane from the
  // normals and the edge's outward direction (faces are counter-clockwise
  // seen from outside, left face on half-edge 2e, so dirA x normalLeftA
  // points out of the left face across the edge). Of n and -n exactly one
  // lies on the arc (angle phi in [0, theta], theta <= pi), and it has
  // cos(phi - theta / 2) >= cos(theta / 2) >= 0 with the bisector while
  // the other has the negative. Orienting by "away from A's centroid"
  // instead fails for a sliver hull: with n near a big face's normal,
  // n . (pointA - centroid) is about half the sliver's thickness, and a
  // hull whose faces are fitted within its tolerance can give it the wrong
  // sign, turning an overlap into an equal separation (fuzz finding
  // sliver_hull_gauss_map_separated_while_overlapping).
  const Vec3 outwardLeftA = edge.dir.cross(edge.normalLeft).normalized();
  const double arcAngle =
      std::atan2(std::max(edge.normalRight.dot(outwardLeftA), 0.0), edge.normalRight.dot(edge.normalLeft));
  edge.bisector = std::cos(0.5 * arcAngle) * edge.normalLeft + std::sin(0.5 * arcAngle) * outwardLeftA;
  return edge;
}

// IsMinkowskiFace(a, b, b x a, c, d, d x c) with (a, b) A's normals and
// (c, d) B's, `sideB` holding B's normals against A's arc plane: B's arc
// must cross A's arc plane first (the cheap test).
bool BuildsMinkowskiFace(const MinkowskiEdgeA& edgeA, std::span<const double> sideB,
                         const SatFrame::Arc& arcB) {
  const double cba = -sideB[static_cast<std::size_t>(arcB.left)];
  const double dba = -sideB[static_cast<std::size_t>(arcB.right)];
  if (!(cba * dba < 0.0)) return false;
  const double adc = edgeA.normalLeft.dot(arcB.cross);
  const double bdc = edgeA.normalRight.dot(arcB.cross);
  return adc * bdc < 0.0 && cba * bdc > 0.0;
}

// Every edge of B against edge `ea` of A (described by `edgeA`), improving
// `best`; returns true on the first pair that separates by more than
// `margin` (the early out).
bool QueryMinkowskiEdgesOfB(const SatFrame& frame, std::size_t ea, const MinkowskiEdgeA& edgeA, double margin,
                            EdgeQuery& best, std::uint64_t& tested, std::uint64_t& prunedCount) {
  const auto verticesA = frame.hullA->Vertices();
  const auto halfEdgesB = frame.hullB->HalfEdges();
  const std::span<const Vec3> verticesB = frame.verticesB;
  const auto edgeCountB = frame.arcsB.size();
  for (std::size_t eb = 0; eb < edgeCountB; ++eb) {
    if (!BuildsMinkowskiFace(edgeA, frame.sideB, frame.arcsB[eb])) {
      ++prunedCount;
      continue;
    }
    ++tested;
    const Vec3& pointB = verticesB[static_cast<std::size_t>(halfEdgesB[2 * eb].origin)];
    const Vec3 dirB = verticesB[static_cast<std::size_t>(halfEdgesB[2 * eb + 1].origin)] - pointB;
    const Vec3 cross = edgeA.dir.cross(dirB);
    const double crossSquared = cross.squaredNorm();
    // Parallel edges: no reliable axis, and the face axes cover it.
    if (crossSquared <= kParallelEdgeSine * kParallelEdgeSine * edgeA.dirSquared * dirB.squaredNorm())
      continue;
    Vec3 n = cross / std::sqrt(crossSquared);
    if (n.dot(edgeA.bisector) < 0.0) n = -n;
    double separation = n.dot(pointB - edgeA.point);
    // The shortcut is never below the projected gap (pA is no higher
    // than A's top on n, pB no lower than B's bottom), so a pair that
    // cannot beat the best so far needs no more work.
    if (!(separation > best.separation)) continue;
    // A pair that would become the best is confirmed by projecting every
    // vertex of both hulls on n (not by hill climbing, which a sliver can
    // stop early; only pairs that improve the best pay the V_A + V_B
    // dots, a few per query). The shortcut assumes the edges are the
    // supports; on an edge far shorter than the hull (a sliver's vertex
    // cluster, 1e-13 m in the fuzz findings) the direction eA is
    // round-off next to its faces' normals, the Gauss map test can pass a
    // pair whose axis is off A's arc, and eA is then not A's support
    // along n. Unconfirmed, such a pair turned an overlap into a
    // separation (by 2.7e-4 m, sliver_hull_gauss_map_separated_while_-
    // overlapping) and, overlapping, claimed 3.6e-8 m less overlap than
    // its axis has, beating A's face of least overlap by more than the
    // preference band, so the reported depth was 1.8e-8 m beyond the true
    // minimum (sliver_edge_axis_beat_face_by_shortcut). The projected gap
    // equals the shortcut, up to round-off, on a true Minkowski face, so
    // the least overlap is still found.
    separation = std::min(separation, LowestAlong(verticesB, n) - HighestAlong(verticesA, n));
    if (separation > best.separation) {
      best = {.edgeA = static_cast<int>(ea), .edgeB = static_cast<int>(eb), .separation = separation};
      if (separation > margin) return true;  // early out on the first separating axis
    }
  }
  return false;
}

// GaussMapPruned mode (Gregorius, GDC 2013): only edge pairs that build a
// face of the Minkowski difference A - B are measured, and those need no
// projection in exact arithmetic (a pair that would become the best is
// still projected once, see QueryMinkowskiEdgesOfB). For such a pair the
// axis n = eA x eB (oriented onto A's arc, away from A's interior) lies on
// both edges' arcs, so edge eA is A's support along n and edge eB is B's
// support along -n: the gap is n . (pB - pA) for any vertex pA of eA and pB
// of eB. The Gauss map test reads B's face normals against A's arc plane
// from a table filled once per edge of A (one dot per face of B instead of
// two per edge pair), and runs the same predicates, on the same numbers,
// as IsMinkowskiFace.
EdgeQuery QueryMinkowskiEdges(SatFrame& frame, double margin, NarrowPhaseStats* stats) {
  const auto faceCountB = frame.planesB.size();
  EdgeQuery best;
  std::uint64_t tested = 0;
  std::uint64_t prunedCount = 0;
  const auto edgeCountA = frame.arcsA.size();
  for (std::size_t ea = 0; ea < edgeCountA; ++ea) {
    const SatFrame::Arc& arcA = frame.arcsA[ea];
    for (std::size_t f = 0; f < faceCountB; ++f) frame.sideB[f] = frame.planesB[f].normal.dot(arcA.cross);
    const MinkowskiEdgeA edgeA = DescribeEdgeOfA(frame, ea);
    if (QueryMinkowskiEdgesOfB(frame, ea, edgeA, margin, best, tested, prunedCount)) break;
  }
  if (stats) {
    stats->edgeAxesTested += tested;
    stats->edgePairsPruned += prunedCount;
  }
  return best;
}

// The edge pair the search met first need not be the pair that touches:
// parallel edges give the same axis and the same projections, and in the
// Full mode so can a pair of non-parallel edges (crossed edges on opposite
// sides of two polyhedra span the same axis). The edge that supports the
// axis passes through p's support vertex along `direction` and lies in the
// support plane, so at that vertex this returns the edge most perpendicular
// to `direction`, and among edges equally so (a tie within kPlaneTolerance,
// e.g. several edges of a face that the axis preference did not pick) the
// one most parallel to `edge`.
int SupportingEdge(const PosedHull& p, const Vec3& direction, int edge) {
  constexpr double kPlaneTolerance = 1e-9;  // |cos| differences below this are ties
  const Vec3 along = p.EdgeDirection(edge).normalized();
  const Vec3 axis = direction.normalized();
  // The support vertex by projection: a climb stalled at a round-off local
  // maximum of a sliver would start the walk from the wrong vertex.
  const int v = ProjectedSupportVertex(p, direction, p.EdgeStart(edge));
  const auto halfEdges = p.hull->HalfEdges();
  const int first = p.hull->VertexEdges()[static_cast<std::size_t>(v)];
  int best = edge;
  double bestTilt = 2.0;
  double bestParallel = -1.0;
  int h = first;
  do {
    const int twin = halfEdges[static_cast<std::size_t>(h)].twin;
    const Vec3 dir = (p.Vertex(p.Origin(twin)) - p.Vertex(v)).normalized();
    const double tilt = std::abs(dir.dot(axis));
    const double parallel = std::abs(dir.dot(along));
    if (tilt < bestTilt - kPlaneTolerance ||
        (tilt <= bestTilt + kPlaneTolerance && parallel > bestParallel)) {
      bestTilt = std::min(bestTilt, tilt);
      bestParallel = parallel;
      best = h >> 1;
    }
    h = halfEdges[static_cast<std::size_t>(twin)].next;
  } while (h != first);
  return best;
}

// Half the diagonal of the hull's vertex bounding box (metres).
double HalfDiagonal(const Hull& hull) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (const Vec3& v : hull.Vertices()) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return 0.5 * (hi - lo).norm();
}

}  // namespace

double SatLengthScale(const Hull& a, const Hull& b) { return std::min(HalfDiagonal(a), HalfDiagonal(b)); }

double RoundOffLengthScale(const Hull& a, const Hull& b) {
  return std::max(HalfDiagonal(a), HalfDiagonal(b));
}

bool IsMinkowskiFace(const Vec3& a, const Vec3& b, const Vec3& bxa, const Vec3& c, const Vec3& d,
                     const Vec3& dxc) {
  // B enters the Minkowski difference negated: its arc is (-c, -d), whose
  // plane normal (-d) x (-c) equals d x c.
  const double cba = -c.dot(bxa);
  const double dba = -d.dot(bxa);
  const double adc = a.dot(dxc);
  const double bdc = b.dot(dxc);
  // The arcs' planes split each other's endpoints, and the arcs lie on the
  // same hemisphere (not antipodal).
  return cba * dba < 0.0 && adc * bdc < 0.0 && cba * bdc > 0.0;
}

double EvaluateSatAxis(const PosedHull& a, const PosedHull& b, const SatAxis& axis, Vec3* normal) {
  // Every axis is measured by projecting every vertex of both hulls: this is
  // the figure the SAT reports and the cache trusts.
  switch (axis.type) {
    case SatAxisType::FaceA: {
      *normal = -a.FaceNormal(axis.indexA);
      return FaceSeparation(a, axis.indexA, b);
    }
    case SatAxisType::FaceB: {
      *normal = b.FaceNormal(axis.indexB);
      return FaceSeparation(b, axis.indexB, a);
    }
    case SatAxisType::EdgePair: {
      Vec3 fromAToB = Vec3::Zero();
      const double separation = EdgeSeparation(a, axis.indexA, a.EdgeDirection(axis.indexA), b, axis.indexB,
                                               b.EdgeDirection(axis.indexB), Extent::Projected, &fromAToB);
      *normal = -fromAToB;
      return separation;
    }
    case SatAxisType::None:
      break;
  }
  return kNegativeInfinity;
}

namespace {

// Temporal coherence: last step's axis very likely still separates. The
// result when the cached axis (valid for this pair of hulls) still
// separates by more than `margin`; nothing otherwise.
std::optional<SatResult> ProbeCachedAxis(const PosedHull& a, const PosedHull& b, double margin,
                                         SatCache* cache, NarrowPhaseStats* stats) {
  const bool cacheValid = cache && cache->hullA == a.hull && cache->hullB == b.hull;
  if (!cacheValid || cache->axis.type == SatAxisType::None) return std::nullopt;
  Vec3 normal = Vec3::Zero();
  const double separation = EvaluateSatAxis(a, b, cache->axis, &normal);
  if (!(separation > margin)) return std::nullopt;
  if (stats) ++stats->satCacheHits;
  cache->separated = true;
  return SatResult{
      .separated = true, .cacheHit = true, .axis = cache->axis, .normal = normal, .separation = separation};
}

// The edge pair the search found, re-picked as the edges that support its
// axis (SupportingEdge), unless those measure differently.
SatAxis SupportingEdgePair(const PosedHull& a, const PosedHull& b, const EdgeQuery& edge, double band) {
  const SatAxis searched{SatAxisType::EdgePair, edge.edgeA, edge.edgeB};
  Vec3 normal = Vec3::Zero();
  const double searchedSeparation = EvaluateSatAxis(a, b, searched, &normal);
  const SatAxis axis{SatAxisType::EdgePair, SupportingEdge(a, -normal, edge.edgeA),
                     SupportingEdge(b, normal, edge.edgeB)};
  // The re-picked edges must measure what the searched pair does; the
  // pair the search measured spans the axis by construction (it skips
  // parallel pairs), so it is kept otherwise. Two ways they differ on a
  // sliver: the supporting edges can be parallel, which spans no axis (an
  // edge of 2e-11 m, its direction round-off, picked at the support vertex
  // next to a box edge it happens to parallel gave a separation of -inf in
  // both modes); and hill climbing can stop at a vertex that is a local
  // maximum only through round-off, so SupportingEdge starts from the
  // wrong vertex and its edge's axis, measured by climbing, reported
  // 1.7e-4 m less overlap than the true minimum (SatSliver case 446).
  Vec3 unused = Vec3::Zero();
  const double repickedSeparation = EvaluateSatAxis(a, b, axis, &unused);
  if (!(std::abs(repickedSeparation - searchedSeparation) <= band)) return searched;
  return axis;
}

// Least overlap, with a bias towards faces of A, then faces of B, then
// edges, inside a band relative to the pair's size (see
// kAxisPreferenceRelative).
SatAxis LeastOverlapAxis(const PosedHull& a, const PosedHull& b, const FaceQuery& faceA,
                         const FaceQuery& faceB, const EdgeQuery& edge) {
  const double band = AxisPreferenceBand(*a.hull, *b.hull);
  SatAxis axis{SatAxisType::FaceA, faceA.face, -1};
  double separation = faceA.separation;
  if (faceB.separation > separation + band) {
    axis = {SatAxisType::FaceB, -1, faceB.face};
    separation = faceB.separation;
  }
  if (edge.edgeA >= 0 && edge.separation > separation + band) axis = SupportingEdgePair(a, b, edge, band);
  return axis;
}

}  // namespace

SatResult RunSat(const PosedHull& a, const PosedHull& b, SatMode mode, double margin, SatCache* cache,
                 NarrowPhaseStats* stats, NarrowPhaseScratch* scratch) {
  if (stats) ++stats->satTests;
  if (std::optional<SatResult> hit = ProbeCachedAxis(a, b, margin, cache, stats)) return *hit;

  SatResult result;
  const auto finish = [&](const SatAxis& axis, bool separated) {
    result.axis = axis;
    result.separated = separated;
    result.separation = EvaluateSatAxis(a, b, axis, &result.normal);
    if (cache) *cache = {.hullA = a.hull, .hullB = b.hull, .axis = axis, .separated = separated};
    return result;
  };

  // The search runs in A's frame (see SatFrame), in the caller's scratch.
  std::optional<NarrowPhaseScratch> own;
  if (!scratch) scratch = &own.emplace();
  SatFrame& frame = scratch->sat;
  frame.FillVertices(a, b);
  const auto facesA = a.hull->Faces();
  const FaceQuery faceA = QueryFaces(
      a.hull->FaceCount(), [&](int f) -> const Plane& { return facesA[static_cast<std::size_t>(f)].plane; },
      *b.hull, frame.verticesB, margin, stats);
  if (faceA.separation > margin) return finish({SatAxisType::FaceA, faceA.face, -1}, true);
  frame.FillPlanes();
  const FaceQuery faceB = QueryFaces(
      b.hull->FaceCount(), [&](int f) -> const Plane& { return frame.planesB[static_cast<std::size_t>(f)]; },
      *a.hull, a.hull->Vertices(), margin, stats);
  if (faceB.separation > margin) return finish({SatAxisType::FaceB, -1, faceB.face}, true);
  EdgeQuery edge;
  if (mode == SatMode::GaussMapPruned) {
    frame.FillArcs();
    edge = QueryMinkowskiEdges(frame, margin, stats);
  } else {
    edge = QueryAllEdges(a, b, margin, stats);
  }
  if (edge.separation > margin) return finish({SatAxisType::EdgePair, edge.edgeA, edge.edgeB}, true);
  return finish(LeastOverlapAxis(a, b, faceA, faceB, edge), false);
}

}  // namespace talus
