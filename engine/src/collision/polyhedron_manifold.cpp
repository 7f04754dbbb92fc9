// Polyhedron-polyhedron contact points: edge contacts, the write-up's
// vertex rule and incident-face clipping (see polyhedron_manifold.h).
#include "collision/polyhedron_manifold.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "collision/manifold_reduction.h"
#include "collision/narrow_phase_scratch.h"

namespace talus {
namespace {

// Which side of the pair a face contact's reference face is on.
struct FaceContact {
  const PosedHull* reference;
  const PosedHull* incident;
  int referenceFace;
  bool referenceIsA;
  Plane plane;           // the reference face's world plane
  double roundOffScale;  // RoundOffLengthScale of the pair (metres)
};

FaceContact MakeFaceContact(const PosedHull& a, const PosedHull& b, const SatResult& sat) {
  const bool referenceIsA = sat.axis.type == SatAxisType::FaceA;
  const PosedHull& reference = referenceIsA ? a : b;
  const int face = referenceIsA ? sat.axis.indexA : sat.axis.indexB;
  return {.reference = &reference,
          .incident = referenceIsA ? &b : &a,
          .referenceFace = face,
          .referenceIsA = referenceIsA,
          .plane = reference.FacePlane(face),
          .roundOffScale = RoundOffLengthScale(*a.hull, *b.hull)};
}

std::uint32_t OrderedFeatureId(const FaceContact& contact, std::uint32_t referenceFeature,
                               std::uint32_t incidentFeature) {
  return contact.referenceIsA ? MakeFeatureId(referenceFeature, incidentFeature)
                              : MakeFeatureId(incidentFeature, referenceFeature);
}

// Whether world point `p` is inside `hull` or within `tolerance` of it.
bool Contains(const PosedHull& hull, const Vec3& p, double tolerance) {
  const Vec3 local = hull.rotation.transpose() * (p - hull.position);
  for (const HullFace& face : hull.hull->Faces()) {
    if (face.plane.SignedDistance(local) > tolerance) return false;
  }
  return true;
}

// A face whose normal is within this cosine of perpendicular to the line
// counts as parallel to it (unitless): a clipped point lies on a side
// plane, perpendicular to the normal, and dividing its round-off distance
// by a round-off rate would give a garbage bound.
constexpr double kParallelFaceCosine = 1e-9;

// How far world point p lies outside `hull` (metres; <= 0 inside).
double OutsideDistance(const PosedHull& hull, const Vec3& p) {
  const Vec3 local = hull.rotation.transpose() * (p - hull.position);
  double worst = -std::numeric_limits<double>::infinity();
  for (const HullFace& face : hull.hull->Faces()) worst = std::max(worst, face.plane.SignedDistance(local));
  return worst;
}

// Round-off of a point's distance to a face plane (metres): the point is a
// few sums and products of world coordinates of about |p| + size (size:
// RoundOffLengthScale, since a clipped corner is made from the larger
// shape's vertices), and is mapped into the hull's frame; each rounds a
// few ulps of those. 16 ulps of |p| + size is under the 64 ulps of the
// largest coordinate that the tests and the SAT check allow a point
// outside a shape (either hull's half diagonal is at most sqrt(3) times
// the largest coordinate of a point of the shapes' boxes), so a point kept
// here passes there.
constexpr double kInsideRoundOffUlps = 16.0;

double PointRoundOff(const Vec3& p, double size) {
  return kInsideRoundOffUlps * std::numeric_limits<double>::epsilon() * (p.cwiseAbs().maxCoeff() + size);
}

// A contact point's position: `midpoint` (midway between the surfaces
// along n) unless it lies outside A or B, then the nearest point on the
// same line that is inside both. The line along the normal through a
// contact point meets both shapes, and where the two overlap along it (the
// overlap the point's depth measures) it meets their intersection; the
// midway point leaves that intersection when a side face leans over it (a
// tilted box's corner) or when the incident shape passes through a thin
// reference shape.
//
// If the two intervals do not meet, the line misses the intersection:
// either by round-off (a line through a corner or along an edge of both
// meets them in one point, and a distance divided by a small rate can
// empty the interval), or truly (a vertex beside the reference face, whose
// line passes the other shape by up to metres). The point returned is then
// the one of the line least outside either shape among the mean of the
// interval ends (the rule before issue 26), the midpoint and the two ends:
// the farther shape's distance is convex along the line and these bracket
// its minimum to a factor of 2, while the mean alone could leave a face
// 1e-9 m behind when the other end's face was nearly parallel to the line.
// `missed` says whether that point is still outside a shape by more than
// round-off (PointRoundOff), i.e. the point is not in contact.
Vec3 InsideBoth(const PosedHull& a, const PosedHull& b, const Vec3& n, const Vec3& midpoint,
                double roundOffScale, bool* missed = nullptr) {
  const double roundOff = PointRoundOff(midpoint, roundOffScale);
  double loA = 0.0;
  double hiA = 0.0;
  double loB = 0.0;
  double hiB = 0.0;
  LineInterval(a, midpoint, n, roundOff, &loA, &hiA);
  LineInterval(b, midpoint, n, roundOff, &loB, &hiB);
  const double lo = std::max(loA, loB);
  const double hi = std::min(hiA, hiB);
  if (missed) *missed = false;
  if (lo <= 0.0 && 0.0 <= hi) return midpoint;
  if (lo <= hi) return midpoint + std::clamp(0.0, lo, hi) * n;
  const auto outside = [&](const Vec3& p) { return std::max(OutsideDistance(a, p), OutsideDistance(b, p)); };
  Vec3 best = midpoint;
  double bestOutside = std::numeric_limits<double>::infinity();
  for (const double t : {0.5 * (lo + hi), 0.0, lo, hi}) {
    if (!std::isfinite(t)) continue;
    const Vec3 candidate = midpoint + t * n;
    const double candidateOutside = outside(candidate);
    if (candidateOutside < bestOutside) {
      best = candidate;
      bestOutside = candidateOutside;
    }
  }
  if (missed) *missed = bestOutside > PointRoundOff(best, roundOffScale);
  return best;
}

// The part of segment p0 p1 (world) inside `hull`, as parameters
// [*t0, *t1] along it; empty when *t0 > *t1.
void SegmentInterval(const PosedHull& hull, const Vec3& p0, const Vec3& p1, double* t0, double* t1) {
  const Vec3 local = hull.rotation.transpose() * (p0 - hull.position);
  const Vec3 direction = hull.rotation.transpose() * (p1 - p0);
  *t0 = 0.0;
  *t1 = 1.0;
  for (const HullFace& face : hull.hull->Faces()) {
    const double distance = face.plane.SignedDistance(local);  // <= 0 inside
    const double rate = face.plane.normal.dot(direction);
    if (rate > 0.0) {
      *t1 = std::min(*t1, -distance / rate);
    } else if (rate < 0.0) {
      *t0 = std::max(*t0, -distance / rate);
    } else if (distance > 0.0) {
      *t0 = std::numeric_limits<double>::infinity();
    }
  }
}

// A point of the intersection of A and B for a contact whose own rule
// found none in contact (every normal line it tried misses the
// intersection: the shapes overlap by more than one of them is thick
// there). Of `start`, the vertices of either hull and the midpoints of the
// stretches of either hull's edges inside the other, the point least
// outside either shape. Two overlapping convex shapes have a vertex of one
// inside the other, or else an edge of one crossing the other, so this
// finds a point inside both to round-off; the edges are searched only
// when no vertex is. (The vertices alone left a point far outside both on
// a hull deep in a box: docs/collision-narrow-phase.md, Edge contact.)
Vec3 PointInIntersection(const PosedHull& a, const PosedHull& b, const Vec3& start, double roundOffScale) {
  const auto outside = [&](const Vec3& p) { return std::max(OutsideDistance(a, p), OutsideDistance(b, p)); };
  Vec3 best = start;
  double bestOutside = outside(start);
  const auto consider = [&](const Vec3& p) {
    const double o = outside(p);
    if (o < bestOutside) {
      best = p;
      bestOutside = o;
    }
  };
  for (const PosedHull* hull : {&a, &b}) {
    for (int v = 0; v < hull->hull->VertexCount(); ++v) consider(hull->Vertex(v));
  }
  if (bestOutside <= PointRoundOff(best, roundOffScale)) return best;
  for (const auto& [edges, other] : {std::pair{&a, &b}, std::pair{&b, &a}}) {
    for (int e = 0; e < edges->hull->EdgeCount(); ++e) {
      const Vec3 p0 = edges->Vertex(edges->EdgeStart(e));
      const Vec3 p1 = edges->Vertex(edges->EdgeEnd(e));
      double t0 = 0.0;
      double t1 = 0.0;
      SegmentInterval(*other, p0, p1, &t0, &t1);
      if (t0 <= t1) consider(p0 + 0.5 * (t0 + t1) * (p1 - p0));
    }
  }
  return best;
}

void BuildEdgeContact(const PosedHull& a, const PosedHull& b, const SatResult& sat, ContactManifold* out) {
  const int ea = sat.axis.indexA;
  const int eb = sat.axis.indexB;
  Vec3 onA = Vec3::Zero();
  Vec3 onB = Vec3::Zero();
  ClosestPointsOfSegments(a.Vertex(a.EdgeStart(ea)), a.Vertex(a.EdgeEnd(ea)), b.Vertex(b.EdgeStart(eb)),
                          b.Vertex(b.EdgeEnd(eb)), &onA, &onB);
  bool missed = false;
  const double roundOffScale = RoundOffLengthScale(*a.hull, *b.hull);
  Vec3 position = InsideBoth(a, b, sat.normal, 0.5 * (onA + onB), roundOffScale, &missed);
  // The line along the normal through the edges' closest points crosses A
  // and B where each is thinner than the depth, so their stretches on it
  // do not meet: a pair deeper than the shapes are thick there (a 5 m hull
  // 1.7 m into another, issue 26's large parallel family). A pair apart
  // along the normal (a speculative contact within the margin) has no
  // intersection to find: its point lies in the gap by design, and such
  // pairs are nearly every miss in a hull pile, where searching them was
  // measured (docs/collision-narrow-phase.md, Edge contact).
  if (missed && out->depth > PointRoundOff(position, roundOffScale))
    position = PointInIntersection(a, b, position, roundOffScale);
  out->pointCount = 1;
  out->points[0] = {
      .position = position,
      .depth = out->depth,
      .featureId = MakeFeatureId(PackFeature(FeatureType::Edge, ea), PackFeature(FeatureType::Edge, eb))};
}

// The incident face: of the faces around the incident polyhedron's deepest
// vertex `deepest` (its support along -referenceNormal, the vertex whose
// distance behind the reference plane is the SAT's depth), the one most
// anti-parallel to the reference normal; ties go to the lower index. The
// deepest vertex is then a corner of the clipped polygon whenever it lies
// over the reference face, so the manifold carries the SAT's depth. (The
// face most anti-parallel over the whole polyhedron need not touch that
// vertex: a slab against a round hull got a point at 2.7 mm where the SAT
// depth was 35.9 mm.) For a box the two rules pick the same face.
int IncidentFace(const PosedHull& incident, const Vec3& referenceNormal, int deepest) {
  const auto halfEdges = incident.hull->HalfEdges();
  const int first = incident.hull->VertexEdges()[static_cast<std::size_t>(deepest)];
  int best = -1;
  double bestDot = std::numeric_limits<double>::infinity();
  int h = first;
  do {
    const int f = halfEdges[static_cast<std::size_t>(h)].face;
    const double d = incident.FaceNormal(f).dot(referenceNormal);
    if (d < bestDot || (d == bestDot && f < best)) {
      bestDot = d;
      best = f;
    }
    h = halfEdges[static_cast<std::size_t>(halfEdges[static_cast<std::size_t>(h)].twin)].next;
  } while (h != first);
  return best;
}

// Sutherland-Hodgman against one side plane (keeps side <= 0). A vertex
// exactly on the plane is kept and makes no crossing, so no duplicates.
// The reference feature where the side planes of reference half-edges
// `before` and `after` meet: their shared vertex when adjacent.
std::uint32_t ReferenceCorner(const PosedHull& ref, int before, int after) {
  const auto edges = ref.hull->HalfEdges();
  if (edges[static_cast<std::size_t>(before)].next == after)
    return PackFeature(FeatureType::Vertex, ref.Origin(after));
  if (edges[static_cast<std::size_t>(after)].next == before)
    return PackFeature(FeatureType::Vertex, ref.Origin(before));
  return PackFeature(FeatureType::Edge, after >> 1);
}

void ClipAgainst(const PosedHull& ref, const std::vector<ClipVertex>& in, const Vec3& sideNormal,
                 double sideOffset, int sideHalfEdge, int incidentFace, std::vector<ClipVertex>* out) {
  const std::uint32_t sideFeature = PackFeature(FeatureType::Edge, sideHalfEdge >> 1);
  out->clear();
  const std::size_t count = in.size();
  for (std::size_t i = 0; i < count; ++i) {
    const ClipVertex& cur = in[i];
    const ClipVertex& next = in[(i + 1) % count];
    const double dc = sideNormal.dot(cur.position) - sideOffset;
    const double dn = sideNormal.dot(next.position) - sideOffset;
    if (dc <= 0.0) out->push_back(cur);
    if ((dc < 0.0 && dn > 0.0) || (dc > 0.0 && dn < 0.0)) {
      const double t = dc / (dc - dn);
      ClipVertex cut;
      cut.position = cur.position + t * (next.position - cur.position);
      // On an incident edge: (incident edge, side edge); on an earlier side
      // plane: the reference corner where the two side planes meet.
      cut.referenceFeature =
          cur.segmentOnReference ? ReferenceCorner(ref, cur.segmentReferenceEdge, sideHalfEdge) : sideFeature;
      cut.incidentFeature =
          cur.segmentOnReference ? PackFeature(FeatureType::Face, incidentFace) : cur.segmentIncident;
      if (dc < 0.0) {
        // Leaving: the polygon now runs along this side plane.
        cut.segmentOnReference = true;
        cut.segmentReferenceEdge = sideHalfEdge;
        cut.segmentIncident = PackFeature(FeatureType::Face, incidentFace);
      } else {
        // Entering: the polygon continues along cur's segment.
        cut.segmentOnReference = cur.segmentOnReference;
        cut.segmentReferenceEdge = cur.segmentReferenceEdge;
        cut.segmentIncident = cur.segmentIncident;
      }
      out->push_back(cut);
    }
  }
}

// The incident face's polygon, each vertex with the features that made it
// (the reference face against an incident vertex, the incident edge that
// leaves it).
void IncidentPolygon(const FaceContact& contact, int incidentFace, std::vector<ClipVertex>& polygon) {
  const PosedHull& inc = *contact.incident;
  const auto halfEdges = inc.hull->HalfEdges();
  polygon.clear();
  const int firstInc = inc.hull->Faces()[static_cast<std::size_t>(incidentFace)].edge;
  int h = firstInc;
  do {
    const int v = inc.Origin(h);
    polygon.push_back({.position = inc.Vertex(v),
                       .referenceFeature = PackFeature(FeatureType::Face, contact.referenceFace),
                       .incidentFeature = PackFeature(FeatureType::Vertex, v),
                       .segmentIncident = PackFeature(FeatureType::Edge, h >> 1),
                       .segmentOnReference = false,
                       .segmentReferenceEdge = -1});
    h = halfEdges[static_cast<std::size_t>(h)].next;
  } while (h != firstInc);
}

// Clips `polygon` against the side planes of the reference face, one edge
// at a time, stopping early once nothing is left.
void ClipToReferenceFace(const FaceContact& contact, int incidentFace, std::vector<ClipVertex>& polygon,
                         std::vector<ClipVertex>& clipped) {
  const PosedHull& ref = *contact.reference;
  const Vec3& n = contact.plane.normal;
  const auto refEdges = ref.hull->HalfEdges();
  const int firstRef = ref.hull->Faces()[static_cast<std::size_t>(contact.referenceFace)].edge;
  int h = firstRef;
  do {
    const int next = refEdges[static_cast<std::size_t>(h)].next;
    const Vec3 v0 = ref.Vertex(ref.Origin(h));
    const Vec3 v1 = ref.Vertex(ref.Origin(next));
    // Outward side normal: edge direction x face normal (faces are CCW).
    const Vec3 side = (v1 - v0).cross(n);
    ClipAgainst(ref, polygon, side, side.dot(v0), h, incidentFace, &clipped);
    std::swap(polygon, clipped);
    h = next;
  } while (h != firstRef && !polygon.empty());
}

// The clipped points within `margin` of the reference plane whose normal
// line meets both shapes, into `kept`; returns the deepest kept depth
// (-inf when none is kept).
double KeepPointsInContact(const FaceContact& contact, const Vec3& normal, double margin,
                           const std::vector<ClipVertex>& polygon, std::vector<ContactPoint>& kept) {
  const PosedHull& a = contact.referenceIsA ? *contact.reference : *contact.incident;
  const PosedHull& b = contact.referenceIsA ? *contact.incident : *contact.reference;
  const Vec3& n = contact.plane.normal;
  kept.clear();
  double deepestKept = -std::numeric_limits<double>::infinity();
  for (const ClipVertex& c : polygon) {
    const double s = contact.plane.SignedDistance(c.position);
    if (s > margin) continue;
    // A clipped point whose normal line misses the intersection of the two
    // shapes is not in contact: the incident face passes below a rim of
    // the reference shape that is thinner there than the depth (a round
    // hull's leaning sides under the reference face's edge). It is
    // dropped; the deepest vertex below keeps the manifold non-empty.
    bool missed = false;
    const Vec3 position = InsideBoth(a, b, normal, c.position - 0.5 * s * n, contact.roundOffScale, &missed);
    if (missed && s < 0.0) continue;  // a speculative point (s >= 0) lies in the gap by design
    deepestKept = std::max(deepestKept, -s);
    kept.push_back({.position = position,
                    .depth = -s,
                    .featureId = OrderedFeatureId(contact, c.referenceFeature, c.incidentFeature)});
  }
  return deepestKept;
}

// Adds the incident hull's deepest vertex to `kept` when clipping lost the
// SAT's depth (see below).
void KeepDeepestVertex(const FaceContact& contact, const Vec3& normal, double depth, int deepest,
                       double deepestKept, std::vector<ContactPoint>& kept) {
  const PosedHull& inc = *contact.incident;
  const PosedHull& a = contact.referenceIsA ? *contact.reference : inc;
  const PosedHull& b = contact.referenceIsA ? inc : *contact.reference;
  const Vec3& n = contact.plane.normal;
  // Kept points within round-off of the SAT's depth already carry it (tied
  // deepest vertices, e.g. a box face resting on a face, differ by ulps of
  // the plane offset and the coordinates).
  const Vec3 deepestVertex = inc.Vertex(deepest);
  const double roundOff = kDepthRoundOffUlps * std::numeric_limits<double>::epsilon() *
                          (std::abs(contact.plane.offset) + deepestVertex.cwiseAbs().maxCoeff());
  if (deepestKept < depth - roundOff || kept.empty()) {
    // The deepest vertex was clipped away (it lies beside the reference
    // face: possible on an axis kept inside the preference band, or when
    // round-off clips a grazing contact away entirely): add it, so the
    // manifold carries the SAT's depth and a touching pair has a point.
    // Its depth is the SAT's own measure of that vertex, so the deepest
    // point equals the manifold's depth.
    //
    // Unless its normal line misses the intersection of the two shapes:
    // then the vertex is not in contact, and no point of the intersection
    // need be as deep along the normal as the projections overlap. It
    // happens on faces within the preference band of parallel (issue 26:
    // hulls 5 m across, faces 1e-7 rad apart, the vertex beside the
    // reference face by metres, and the point it gave up to 1.1 m outside
    // a shape), and on any pair whose deepest incident vertex lies beside
    // a small reference face. The kept points then hold the contact with
    // their own, shallower depths, and the manifold still reports the
    // SAT's depth: the projections' overlap, which is what separates the
    // shapes. (Carrying the deepest kept point's depth instead reported
    // less than the minimum translation distance: 0.1718 m against 0.1767
    // m on fuzz finding clipped_vertex_missed_depth_below_minimum_overlap.)
    const double s = contact.plane.SignedDistance(deepestVertex);
    bool missed = false;
    Vec3 position = InsideBoth(a, b, normal, deepestVertex - 0.5 * s * n, contact.roundOffScale, &missed);
    // With nothing else kept the manifold still needs a point in contact:
    // one of the intersection, if the vertex's line misses it.
    if (missed && s < 0.0 && kept.empty())
      position = PointInIntersection(a, b, position, contact.roundOffScale);
    if (!missed || s >= 0.0 || kept.empty()) {
      kept.push_back(
          {.position = position,
           .depth = std::max(-s, depth),
           .featureId = OrderedFeatureId(contact, PackFeature(FeatureType::Face, contact.referenceFace),
                                         PackFeature(FeatureType::Vertex, deepest))});
    }
  }
}

// Fills `points` and returns their count. The manifold keeps the SAT's
// depth; the deepest point carries it unless the SAT's deepest vertex is
// not in contact (see KeepDeepestVertex).
int BuildClippedPoints(const FaceContact& contact, const Vec3& normal, double depth, double margin,
                       ManifoldScratch& scratch, ContactPoint* points) {
  const PosedHull& inc = *contact.incident;
  const Vec3& n = contact.plane.normal;
  const int deepest = inc.Support(-n, 0);
  const int incidentFace = IncidentFace(inc, n, deepest);
  IncidentPolygon(contact, incidentFace, scratch.polygon);
  ClipToReferenceFace(contact, incidentFace, scratch.polygon, scratch.clipped);
  const double deepestKept = KeepPointsInContact(contact, normal, margin, scratch.polygon, scratch.kept);
  KeepDeepestVertex(contact, normal, depth, deepest, deepestKept, scratch.kept);
  return ReduceContactPoints(scratch.kept, n, kClippedMaxPoints, points);
}

int BuildWriteUpPoints(const FaceContact& contact, const Vec3& normal, double depth, ManifoldScratch& scratch,
                       ContactPoint* points) {
  const PosedHull& ref = *contact.reference;
  const PosedHull& inc = *contact.incident;
  const PosedHull& a = contact.referenceIsA ? ref : inc;
  const PosedHull& b = contact.referenceIsA ? inc : ref;
  const Vec3& n = contact.plane.normal;
  const double tolerance = WriteUpTolerance(*ref.hull, *inc.hull);
  std::vector<ContactPoint>& found = scratch.found;
  found.clear();
  // Each point is moved onto the plane midway between the surfaces, then
  // along the normal into both shapes where it left one (InsideBoth).
  const auto midway = [&](const Vec3& p) {
    return InsideBoth(a, b, normal, p - (contact.plane.SignedDistance(p) + 0.5 * depth) * n,
                      contact.roundOffScale);
  };
  for (int v = 0; v < inc.hull->VertexCount(); ++v) {
    const Vec3 p = inc.Vertex(v);
    if (contact.plane.SignedDistance(p) > tolerance) continue;
    if (!Contains(ref, p, tolerance)) continue;
    found.push_back(
        {.position = midway(p),
         .depth = depth,
         .featureId = OrderedFeatureId(contact, PackFeature(FeatureType::Face, contact.referenceFace),
                                       PackFeature(FeatureType::Vertex, v))});
  }
  for (int v = 0; v < ref.hull->VertexCount(); ++v) {
    const Vec3 p = ref.Vertex(v);
    if (contact.plane.SignedDistance(p) < -tolerance) continue;
    if (!Contains(inc, p, tolerance)) continue;
    found.push_back({.position = midway(p),
                     .depth = depth,
                     .featureId = OrderedFeatureId(contact, PackFeature(FeatureType::Vertex, v),
                                                   PackFeature(FeatureType::None, 0))});
  }
  return ReduceContactPoints(found, n, kMaxManifoldPoints, points);
}

}  // namespace

// A face parallel to the line excludes it only when p is farther out than
// the hull's own tolerance or the point's round-off, whichever is larger:
// a corner clipped onto a small face's side plane lies on it to the
// round-off of the larger shape's coordinates, which can be ten times the
// small hull's tolerance (docs/collision-narrow-phase.md, manifold normal).
void LineInterval(const PosedHull& hull, const Vec3& p, const Vec3& n, double roundOff, double* lo,
                  double* hi) {
  const Vec3 local = hull.rotation.transpose() * (p - hull.position);
  const Vec3 direction = hull.rotation.transpose() * n;
  *lo = -std::numeric_limits<double>::infinity();
  *hi = std::numeric_limits<double>::infinity();
  for (const HullFace& face : hull.hull->Faces()) {
    const double distance = face.plane.SignedDistance(local);  // <= 0 inside
    const double rate = face.plane.normal.dot(direction);
    if (rate > kParallelFaceCosine) {
      *hi = std::min(*hi, -distance / rate);
    } else if (rate < -kParallelFaceCosine) {
      *lo = std::max(*lo, -distance / rate);
    } else if (distance > std::max(hull.hull->Tolerance(), roundOff)) {
      *lo = std::numeric_limits<double>::infinity();  // parallel to the face, outside it
    }
  }
}

double WriteUpTolerance(const Hull& a, const Hull& b) {
  static_assert(kWriteUpPlaneTolerance == kWriteUpInsideTolerance, "one slop for both tests");
  return std::min(kWriteUpPlaneTolerance, kWriteUpRelative * SatLengthScale(a, b));
}

void ClosestPointsOfSegments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, Vec3* onP,
                             Vec3* onQ) {
  const Vec3 d1 = p1 - p0;
  const Vec3 d2 = q1 - q0;
  const Vec3 r = p0 - q0;
  const double a = d1.squaredNorm();
  const double e = d2.squaredNorm();
  const double f = d2.dot(r);
  double s = 0.0;
  double t = 0.0;
  if (a <= 0.0 && e > 0.0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else if (a > 0.0) {
    const double c = d1.dot(r);
    if (e <= 0.0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2);
      const double denom = a * e - b * b;
      // Parallel segments (denom 0): any s works; take the start.
      s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  *onP = p0 + s * d1;
  *onQ = q0 + t * d2;
}

void BuildPolyhedronManifold(const PosedHull& a, const PosedHull& b, const SatResult& sat, ManifoldMode mode,
                             double margin, ContactManifold* out, NarrowPhaseScratch* scratch) {
  std::optional<NarrowPhaseScratch> own;
  if (!scratch) scratch = &own.emplace();
  ManifoldScratch& clip = scratch->manifold;
  out->normal = sat.normal;
  out->depth = -sat.separation;
  out->pointCount = 0;
  if (sat.axis.type == SatAxisType::EdgePair) {
    BuildEdgeContact(a, b, sat, out);
    return;
  }
  const FaceContact contact = MakeFaceContact(a, b, sat);
  if (mode == ManifoldMode::WriteUp) {
    out->pointCount = BuildWriteUpPoints(contact, out->normal, out->depth, clip, out->points.data());
    if (out->pointCount > 0) return;
    // No vertex qualifies (e.g. two bars crossed face to face): the
    // write-up's rule finds nothing, so use the clipped points instead.
  }
  out->pointCount = BuildClippedPoints(contact, out->normal, out->depth, margin, clip, out->points.data());
}

}  // namespace talus
