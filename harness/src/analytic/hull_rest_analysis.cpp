// Resting faces of a hull (see talus/harness/analytic/hull_rest_analysis.h).
#include "talus/harness/analytic/hull_rest_analysis.h"

#include <algorithm>
#include <limits>

#include "talus/hull_builder.h"
#include "talus/mass_properties.h"

namespace talus::harness {

int HullRestAnalysis::NearestFace(const Vec3& direction) const {
  const Vec3 unit = direction.normalized();
  int best = -1;
  double bestDot = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < static_cast<int>(faces.size()); ++i) {
    const double dot = faces[i].normal.dot(unit);
    if (dot > bestDot) {
      bestDot = dot;
      best = i;
    }
  }
  return best;
}

Result<HullRestAnalysis> AnalyseHullRest(std::span<const Vec3> points) {
  auto hull = BuildHull(points);
  if (!hull) return hull.GetError();
  // Density 1: only the centroid is used, which does not depend on it.
  auto mass = ComputeMassProperties(hull.Value(), 1.0);
  if (!mass) return mass.GetError();
  HullRestAnalysis analysis;
  analysis.centroid = mass.Value().centerOfMass;
  const std::span<const Vec3> vertices = hull.Value().Vertices();
  double size = 0.0;
  for (const Vec3& v : vertices) size = std::max(size, (v - analysis.centroid).norm());
  for (int f = 0; f < hull.Value().FaceCount(); ++f) {
    const Plane& plane = hull.Value().Faces()[f].plane;
    HullRestFace face;
    face.normal = plane.normal;
    face.height = -plane.SignedDistance(analysis.centroid);
    // The margin is the smallest in-plane distance from the projected
    // centroid to an edge line; loops run counter-clockwise seen from
    // outside, so n x edge points into the face.
    const Vec3 projected = analysis.centroid + face.height * plane.normal;
    const std::vector<int> loop = hull.Value().FaceVertices(f);
    face.margin = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < loop.size(); ++i) {
      const Vec3& a = vertices[loop[i]];
      const Vec3& b = vertices[loop[(i + 1) % loop.size()]];
      const Vec3 inward = plane.normal.cross(b - a).normalized();
      face.margin = std::min(face.margin, (projected - a).dot(inward));
    }
    face.stable = face.margin > 1e-9 * size;
    analysis.faces.push_back(face);
  }
  return analysis;
}

}  // namespace talus::harness
