// The Minkowski-difference truth (see the header for the idea). Every loop
// runs over arrays in index order, so the answer is deterministic.
#include "talus/reference/minkowski_truth.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "talus/hull_builder.h"
#include "talus/hull_queries.h"
#include "talus/mass_properties.h"
#include "talus/reference/qhull_oracle.h"

namespace talus::reference {
namespace {

// Plane offsets within this of the minimum count as ties (metres).
constexpr double kTieTolerance = 1e-9;

}  // namespace

std::vector<Vec3> MinkowskiDifferencePoints(const Hull& a, const Transform& xfA, const Hull& b,
                                            const Transform& xfB) {
  std::vector<Vec3> worldB;
  worldB.reserve(static_cast<std::size_t>(b.VertexCount()));
  for (const Vec3& v : b.Vertices()) worldB.push_back(xfB.Apply(v));
  std::vector<Vec3> points;
  points.reserve(static_cast<std::size_t>(a.VertexCount()) * worldB.size());
  for (const Vec3& va : a.Vertices()) {
    const Vec3 pa = xfA.Apply(va);
    for (const Vec3& pb : worldB) points.push_back(pa - pb);
  }
  return points;
}

Vec3 ClosestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Voronoi regions of the triangle: vertices, then edges, then the face.
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const Vec3 ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denominator = 1.0 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

Result<PenetrationTruth> ComputePenetrationTruth(const Hull& a, const Transform& xfA, const Hull& b,
                                                 const Transform& xfB) {
  const std::vector<Vec3> points = MinkowskiDifferencePoints(a, xfA, b, xfB);
  Result<Hull> built = BuildHull(points);
  if (!built) return Error{"Minkowski difference: " + built.GetError().message};
  const Hull& d = built.Value();
  PenetrationTruth truth;
  truth.differenceVertices = d.VertexCount();
  truth.differenceFaces = d.FaceCount();

  // Largest signed distance of the origin over the face planes: <= 0 when
  // the origin is inside; then -max is the smallest offset.
  double maxDistance = -std::numeric_limits<double>::infinity();
  int maxFace = 0;
  for (int f = 0; f < d.FaceCount(); ++f) {
    const double distance = -d.Faces()[static_cast<std::size_t>(f)].plane.offset;
    if (distance > maxDistance) {
      maxDistance = distance;
      maxFace = f;
    }
  }
  truth.intersecting = maxDistance <= 0.0;
  if (truth.intersecting) {
    truth.signedDistance = maxDistance;
    truth.normal = -d.Faces()[static_cast<std::size_t>(maxFace)].plane.normal;
    for (const HullFace& face : d.Faces()) {
      if (-face.plane.offset >= maxDistance - kTieTolerance) ++truth.minimumFaces;
    }
    return truth;
  }

  // Outside: the closest point c of D's boundary, over its triangles.
  // c = a - b for the closest points, so A lies along +c from B.
  double best = std::numeric_limits<double>::infinity();
  Vec3 closest = Vec3::Zero();
  const auto vertices = d.Vertices();
  for (const std::array<int, 3>& t : d.Triangulate()) {
    const Vec3 q = ClosestPointOnTriangle(Vec3::Zero(), vertices[static_cast<std::size_t>(t[0])],
                                          vertices[static_cast<std::size_t>(t[1])],
                                          vertices[static_cast<std::size_t>(t[2])]);
    if (q.norm() < best) {
      best = q.norm();
      closest = q;
    }
  }
  truth.signedDistance = best;
  if (best > 0.0) truth.normal = closest / best;
  truth.minimumFaces = 1;
  return truth;
}

Result<bool> CheckMinkowskiWithQhull(const Hull& a, const Transform& xfA, const Hull& b, const Transform& xfB,
                                     double relativeTolerance) {
  const std::vector<Vec3> points = MinkowskiDifferencePoints(a, xfA, b, xfB);
  Result<Hull> built = BuildHull(points);
  if (!built) return Error{"BuildHull: " + built.GetError().message};
  Result<QhullHull> qhull = QhullConvexHull(points);
  if (!qhull) return Error{"qhull: " + qhull.GetError().message};
  Result<MassProperties> mass = ComputeMassProperties(built.Value(), 1.0);
  if (!mass) return Error{"mass properties: " + mass.GetError().message};
  const double volume = mass.Value().volume;
  const double qhullVolume = qhull.Value().volume;
  if (std::abs(volume - qhullVolume) > relativeTolerance * std::max(volume, qhullVolume)) {
    return Error{"volume " + std::to_string(volume) + " (BuildHull) vs " + std::to_string(qhullVolume) +
                 " (qhull)"};
  }
  const double tolerance = built.Value().Tolerance();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!ContainsPoint(built.Value(), points[i], tolerance)) {
      return Error{"difference point " + std::to_string(i) + " lies outside the built hull"};
    }
  }
  return true;
}

}  // namespace talus::reference
