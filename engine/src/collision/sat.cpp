// The Separating Axis Test: face queries, edge queries (all pairs or Gauss
// map pruned), the cached-axis probe and the choice of the contact axis.
//
// Every candidate is measured the same way in both modes, so the two modes
// compute bit-identical numbers for any axis they both test:
// - a face of A with world plane (n, d): separation = min over B of n.b - d;
// - a face of B likewise with the roles swapped;
// - an edge pair: n = eA x eB normalised, both polyhedra projected on n,
//   separation = the larger of the two one-sided gaps (B beyond A along n,
//   or along -n), with supports found by hill climbing from the edges' own
//   vertices (which are the supports when the pair is a Minkowski face).
// The minimum overlap over all E^2 edge axes equals the minimum over the
// Minkowski-face pairs (the overlap along a direction is the support
// distance of A - B, smallest at one of its faces), which is why pruning
// loses nothing (Gregorius, GDC 2013).
#include "collision/sat.h"

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

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

// Separation of face f of `p` against `q`: how far q's deepest vertex is in
// front of the face plane. `start` is q's support hint.
double FaceSeparation(const PosedHull& p, int f, const PosedHull& q, int* start) {
  const Plane plane = p.FacePlane(f);
  *start = q.Support(-plane.normal, *start);
  return plane.normal.dot(q.Vertex(*start)) - plane.offset;
}

// The face of `p` whose plane q is farthest in front of; stops at the first
// one beyond `margin`.
FaceQuery QueryFaces(const PosedHull& p, const PosedHull& q, double margin, NarrowPhaseStats* stats) {
  FaceQuery best;
  int start = 0;
  const int faceCount = p.hull->FaceCount();
  int tested = 0;
  for (int f = 0; f < faceCount; ++f) {
    ++tested;
    const double separation = FaceSeparation(p, f, q, &start);
    if (separation > best.separation) {
      best = {.face = f, .separation = separation};
      if (separation > margin) break;
    }
  }
  if (stats) stats->faceAxesTested += static_cast<std::uint64_t>(tested);
  return best;
}

// The projection gap along the cross product of edges ea (of a) and eb (of
// b); `axis` gets the direction from A towards B that achieves it.
double EdgeSeparation(const PosedHull& a, int ea, const Vec3& dirA, const PosedHull& b, int eb,
                      const Vec3& dirB, Vec3* axis) {
  const Vec3 cross = dirA.cross(dirB);
  const double crossSquared = cross.squaredNorm();
  if (crossSquared <= kParallelEdgeSine * kParallelEdgeSine * dirA.squaredNorm() * dirB.squaredNorm()) {
    return kNegativeInfinity;
  }
  const Vec3 n = cross / std::sqrt(crossSquared);
  const int startA = a.EdgeStart(ea);
  const int startB = b.EdgeStart(eb);
  const double highA = a.SupportDistance(n, startA);
  const double lowA = -a.SupportDistance(-n, startA);
  const double highB = b.SupportDistance(n, startB);
  const double lowB = -b.SupportDistance(-n, startB);
  const double alongPlus = lowB - highA;   // B beyond A along +n
  const double alongMinus = lowA - highB;  // B beyond A along -n
  if (alongMinus > alongPlus) {
    *axis = -n;
    return alongMinus;
  }
  *axis = n;
  return alongPlus;
}

// World-space edge data reused across the E_A x E_B loop.
struct EdgeFrame {
  std::vector<Vec3> direction;    // edge vector, world
  std::vector<Vec3> normalLeft;   // normal of the face of half-edge 2e
  std::vector<Vec3> normalRight;  // normal of the face of half-edge 2e + 1
  std::vector<Vec3> arcCross;     // normalRight x normalLeft (the arc's plane)

  void Fill(const PosedHull& p, bool withNormals) {
    const int edgeCount = p.hull->EdgeCount();
    const auto halfEdges = p.hull->HalfEdges();
    direction.resize(static_cast<std::size_t>(edgeCount));
    if (withNormals) {
      normalLeft.resize(direction.size());
      normalRight.resize(direction.size());
      arcCross.resize(direction.size());
    }
    for (int e = 0; e < edgeCount; ++e) {
      const auto i = static_cast<std::size_t>(e);
      direction[i] = p.EdgeDirection(e);
      if (!withNormals) continue;
      normalLeft[i] = p.FaceNormal(halfEdges[2 * i].face);
      normalRight[i] = p.FaceNormal(halfEdges[2 * i + 1].face);
      arcCross[i] = normalRight[i].cross(normalLeft[i]);
    }
  }
};

EdgeQuery QueryEdges(const PosedHull& a, const PosedHull& b, SatMode mode, double margin,
                     NarrowPhaseStats* stats) {
  // Scratch kept per thread so a query allocates only when a hull outgrows
  // it; contents never leak into results.
  thread_local EdgeFrame frameA;
  thread_local EdgeFrame frameB;
  const bool pruned = mode == SatMode::GaussMapPruned;
  frameA.Fill(a, pruned);
  frameB.Fill(b, pruned);
  EdgeQuery best;
  std::uint64_t tested = 0;
  std::uint64_t prunedCount = 0;
  const int edgeCountA = a.hull->EdgeCount();
  const int edgeCountB = b.hull->EdgeCount();
  for (int ea = 0; ea < edgeCountA; ++ea) {
    const auto i = static_cast<std::size_t>(ea);
    for (int eb = 0; eb < edgeCountB; ++eb) {
      const auto j = static_cast<std::size_t>(eb);
      if (pruned && !IsMinkowskiFace(frameA.normalLeft[i], frameA.normalRight[i], frameA.arcCross[i],
                                     frameB.normalLeft[j], frameB.normalRight[j], frameB.arcCross[j])) {
        ++prunedCount;
        continue;
      }
      ++tested;
      Vec3 axis = Vec3::Zero();
      const double separation = EdgeSeparation(a, ea, frameA.direction[i], b, eb, frameB.direction[j], &axis);
      if (separation > best.separation) {
        best = {.edgeA = ea, .edgeB = eb, .separation = separation};
        if (separation > margin) {
          ea = edgeCountA;  // early out on the first separating axis
          break;
        }
      }
    }
  }
  if (stats) {
    stats->edgeAxesTested += tested;
    stats->edgePairsPruned += prunedCount;
  }
  return best;
}

// Parallel edges give the same axis and the same projections, so the edge
// pair the search met first need not be the pair that touches. This returns
// the edge of `p` parallel to `edge` (or closest to it) through p's support
// vertex along `direction`: the edge that actually supports the axis.
int SupportingEdge(const PosedHull& p, const Vec3& direction, int edge) {
  const Vec3 along = p.EdgeDirection(edge).normalized();
  const int v = p.Support(direction, p.EdgeStart(edge));
  const auto halfEdges = p.hull->HalfEdges();
  const int first = p.hull->VertexEdges()[static_cast<std::size_t>(v)];
  int best = edge;
  double bestCosine = -1.0;
  int h = first;
  do {
    const int twin = halfEdges[static_cast<std::size_t>(h)].twin;
    const double cosine = std::abs((p.Vertex(p.Origin(twin)) - p.Vertex(v)).normalized().dot(along));
    if (cosine > bestCosine) {
      bestCosine = cosine;
      best = h >> 1;
    }
    h = halfEdges[static_cast<std::size_t>(twin)].next;
  } while (h != first);
  return best;
}

}  // namespace

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
  int start = 0;
  switch (axis.type) {
    case SatAxisType::FaceA: {
      *normal = -a.FaceNormal(axis.indexA);
      return FaceSeparation(a, axis.indexA, b, &start);
    }
    case SatAxisType::FaceB: {
      *normal = b.FaceNormal(axis.indexB);
      return FaceSeparation(b, axis.indexB, a, &start);
    }
    case SatAxisType::EdgePair: {
      Vec3 fromAToB = Vec3::Zero();
      const double separation = EdgeSeparation(a, axis.indexA, a.EdgeDirection(axis.indexA), b, axis.indexB,
                                               b.EdgeDirection(axis.indexB), &fromAToB);
      *normal = -fromAToB;
      return separation;
    }
    case SatAxisType::None:
      break;
  }
  return kNegativeInfinity;
}

SatResult RunSat(const PosedHull& a, const PosedHull& b, SatMode mode, double margin, SatCache* cache,
                 NarrowPhaseStats* stats) {
  if (stats) ++stats->satTests;
  SatResult result;
  const bool cacheValid = cache && cache->hullA == a.hull && cache->hullB == b.hull;

  // Temporal coherence: last step's axis very likely still separates.
  if (cacheValid && cache->axis.type != SatAxisType::None) {
    Vec3 normal = Vec3::Zero();
    const double separation = EvaluateSatAxis(a, b, cache->axis, &normal);
    if (separation > margin) {
      if (stats) ++stats->satCacheHits;
      cache->separated = true;
      return {.separated = true,
              .cacheHit = true,
              .axis = cache->axis,
              .normal = normal,
              .separation = separation};
    }
  }

  const auto finish = [&](const SatAxis& axis, bool separated) {
    result.axis = axis;
    result.separated = separated;
    result.separation = EvaluateSatAxis(a, b, axis, &result.normal);
    if (cache) *cache = {.hullA = a.hull, .hullB = b.hull, .axis = axis, .separated = separated};
    return result;
  };

  const FaceQuery faceA = QueryFaces(a, b, margin, stats);
  if (faceA.separation > margin) return finish({SatAxisType::FaceA, faceA.face, -1}, true);
  const FaceQuery faceB = QueryFaces(b, a, margin, stats);
  if (faceB.separation > margin) return finish({SatAxisType::FaceB, -1, faceB.face}, true);
  const EdgeQuery edge = QueryEdges(a, b, mode, margin, stats);
  if (edge.separation > margin) return finish({SatAxisType::EdgePair, edge.edgeA, edge.edgeB}, true);

  // Least overlap, with a bias towards faces of A, then faces of B, then
  // edges (see kAxisPreferenceTolerance).
  SatAxis axis{SatAxisType::FaceA, faceA.face, -1};
  double separation = faceA.separation;
  if (faceB.separation > separation + kAxisPreferenceTolerance) {
    axis = {SatAxisType::FaceB, -1, faceB.face};
    separation = faceB.separation;
  }
  if (edge.edgeA >= 0 && edge.separation > separation + kAxisPreferenceTolerance) {
    Vec3 normal = Vec3::Zero();
    EvaluateSatAxis(a, b, {SatAxisType::EdgePair, edge.edgeA, edge.edgeB}, &normal);
    axis = {SatAxisType::EdgePair, SupportingEdge(a, -normal, edge.edgeA),
            SupportingEdge(b, normal, edge.edgeB)};
  }
  return finish(axis, false);
}

}  // namespace talus
