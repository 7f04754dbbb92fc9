// Polyhedron-polyhedron contact points: edge contacts, the write-up's
// vertex rule and incident-face clipping (see polyhedron_manifold.h).
#include "collision/polyhedron_manifold.h"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

#include "collision/manifold_reduction.h"

namespace talus {
namespace {

// Which side of the pair a face contact's reference face is on.
struct FaceContact {
  const PosedHull* reference;
  const PosedHull* incident;
  int referenceFace;
  bool referenceIsA;
  Plane plane;  // the reference face's world plane
};

FaceContact MakeFaceContact(const PosedHull& a, const PosedHull& b, const SatResult& sat) {
  const bool referenceIsA = sat.axis.type == SatAxisType::FaceA;
  const PosedHull& reference = referenceIsA ? a : b;
  const int face = referenceIsA ? sat.axis.indexA : sat.axis.indexB;
  return {.reference = &reference,
          .incident = referenceIsA ? &b : &a,
          .referenceFace = face,
          .referenceIsA = referenceIsA,
          .plane = reference.FacePlane(face)};
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

void BuildEdgeContact(const PosedHull& a, const PosedHull& b, const SatResult& sat, ContactManifold* out) {
  const int ea = sat.axis.indexA;
  const int eb = sat.axis.indexB;
  Vec3 onA = Vec3::Zero();
  Vec3 onB = Vec3::Zero();
  ClosestPointsOfSegments(a.Vertex(a.EdgeStart(ea)), a.Vertex(a.EdgeEnd(ea)), b.Vertex(b.EdgeStart(eb)),
                          b.Vertex(b.EdgeEnd(eb)), &onA, &onB);
  out->pointCount = 1;
  out->points[0] = {
      .position = 0.5 * (onA + onB),
      .depth = out->depth,
      .featureId = MakeFeatureId(PackFeature(FeatureType::Edge, ea), PackFeature(FeatureType::Edge, eb))};
}

// A polygon vertex during clipping: its position, the features that made
// it, and the line the polygon follows to the next vertex (an incident edge,
// or a reference side plane already clipped against).
struct ClipVertex {
  Vec3 position;
  std::uint32_t referenceFeature;
  std::uint32_t incidentFeature;
  std::uint32_t segmentIncident;    // incident feature of the segment to the next vertex
  bool segmentOnReference = false;  // the segment lies on a reference side plane
  int segmentReferenceEdge = -1;    // the reference half-edge of that side plane
};

int IncidentFace(const PosedHull& incident, const Vec3& referenceNormal) {
  int best = 0;
  double bestDot = std::numeric_limits<double>::infinity();
  for (int f = 0; f < incident.hull->FaceCount(); ++f) {
    const double d = incident.FaceNormal(f).dot(referenceNormal);
    if (d < bestDot) {
      bestDot = d;
      best = f;
    }
  }
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

int BuildClippedPoints(const FaceContact& contact, double depth, double margin, ContactPoint* points) {
  const PosedHull& ref = *contact.reference;
  const PosedHull& inc = *contact.incident;
  const Vec3& n = contact.plane.normal;
  const auto halfEdges = inc.hull->HalfEdges();
  const int incidentFace = IncidentFace(inc, n);

  thread_local std::vector<ClipVertex> polygon;
  thread_local std::vector<ClipVertex> clipped;
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

  const auto refEdges = ref.hull->HalfEdges();
  const int firstRef = ref.hull->Faces()[static_cast<std::size_t>(contact.referenceFace)].edge;
  h = firstRef;
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

  thread_local std::vector<ContactPoint> kept;
  kept.clear();
  for (const ClipVertex& c : polygon) {
    const double s = contact.plane.SignedDistance(c.position);
    if (s > margin) continue;
    kept.push_back({.position = c.position - 0.5 * s * n,
                    .depth = -s,
                    .featureId = OrderedFeatureId(contact, c.referenceFeature, c.incidentFeature)});
  }
  if (kept.empty()) {
    // Round-off can clip a grazing contact away entirely: fall back to the
    // incident polyhedron's deepest vertex so a touching pair has a point.
    const int v = inc.Support(-n, inc.Origin(firstInc));
    const double s = contact.plane.SignedDistance(inc.Vertex(v));
    kept.push_back(
        {.position = inc.Vertex(v) - 0.5 * s * n,
         .depth = std::max(-s, depth),
         .featureId = OrderedFeatureId(contact, PackFeature(FeatureType::Face, contact.referenceFace),
                                       PackFeature(FeatureType::Vertex, v))});
  }
  return ReduceContactPoints(kept, n, kClippedMaxPoints, points);
}

int BuildWriteUpPoints(const FaceContact& contact, double depth, ContactPoint* points) {
  const PosedHull& ref = *contact.reference;
  const PosedHull& inc = *contact.incident;
  const Vec3& n = contact.plane.normal;
  thread_local std::vector<ContactPoint> found;
  found.clear();
  // Each point is moved onto the plane midway between the surfaces.
  const auto midway = [&](const Vec3& p) { return p - (contact.plane.SignedDistance(p) + 0.5 * depth) * n; };
  for (int v = 0; v < inc.hull->VertexCount(); ++v) {
    const Vec3 p = inc.Vertex(v);
    if (contact.plane.SignedDistance(p) > kWriteUpPlaneTolerance) continue;
    if (!Contains(ref, p, kWriteUpInsideTolerance)) continue;
    found.push_back(
        {.position = midway(p),
         .depth = depth,
         .featureId = OrderedFeatureId(contact, PackFeature(FeatureType::Face, contact.referenceFace),
                                       PackFeature(FeatureType::Vertex, v))});
  }
  for (int v = 0; v < ref.hull->VertexCount(); ++v) {
    const Vec3 p = ref.Vertex(v);
    if (contact.plane.SignedDistance(p) < -kWriteUpPlaneTolerance) continue;
    if (!Contains(inc, p, kWriteUpInsideTolerance)) continue;
    found.push_back({.position = midway(p),
                     .depth = depth,
                     .featureId = OrderedFeatureId(contact, PackFeature(FeatureType::Vertex, v),
                                                   PackFeature(FeatureType::None, 0))});
  }
  return ReduceContactPoints(found, n, kMaxManifoldPoints, points);
}

}  // namespace

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
                             double margin, ContactManifold* out) {
  out->normal = sat.normal;
  out->depth = -sat.separation;
  out->pointCount = 0;
  if (sat.axis.type == SatAxisType::EdgePair) {
    BuildEdgeContact(a, b, sat, out);
    return;
  }
  const FaceContact contact = MakeFaceContact(a, b, sat);
  if (mode == ManifoldMode::WriteUp) {
    out->pointCount = BuildWriteUpPoints(contact, out->depth, out->points.data());
    if (out->pointCount > 0) return;
    // No vertex qualifies (e.g. two bars crossed face to face): the
    // write-up's rule finds nothing, so use the clipped points instead.
  }
  out->pointCount = BuildClippedPoints(contact, out->depth, margin, out->points.data());
}

}  // namespace talus
