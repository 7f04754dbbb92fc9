// Exact mass properties of a uniform-density convex polyhedron.
//
// Method (the divergence theorem, in the simplest closed form; compare
// Mirtich, "Fast and Accurate Computation of Polyhedral Mass Properties",
// 1996, and Tonon, "Explicit Exact Formulas for the 3-D Tetrahedron Inertia
// Tensor in Terms of its Vertex Coordinates", 2004): pick a reference point
// r and fan every polygonal face from its first vertex into triangles
// (a, b, c). Each triangle and r span a tetrahedron whose signed volume is
// det[a - r, b - r, c - r] / 6, positive when the triangle is
// counter-clockwise seen from outside. Summing signed tetrahedra over the
// closed surface integrates exactly over the solid, whatever r is. For one
// tetrahedron with a vertex at the origin and the others at p, q, s:
//
//   volume            V = det / 6
//   first moment      integral of x dV = V (p + q + s) / 4
//   second moment     integral of x x^T dV
//                       = det / 120 (p p^T + q q^T + s s^T + S S^T),
//                     S = p + q + s.
//
// From the summed second moment C about r, the centre of mass c gives
// C_c = C - V (c - r)(c - r)^T (the parallel-axis theorem for covariance),
// and the inertia tensor is density (trace(C_c) I - C_c).
//
// Accuracy: r is the vertex average, so the coordinates entering the cubic
// and quadratic products are of the hull's size, not of its distance from
// the origin; a 1 m box centred 1e4 m away then loses no more digits than one
// at the origin. Only the final centre of mass is shifted back by r.
#include <cmath>
#include <string>

#include "talus/mass_properties.h"

namespace talus {
namespace {

// Volume integrals of a closed, outward-oriented polygon mesh about a
// reference point, before density is applied.
struct VolumeIntegrals {
  double volume = 0.0;               // m^3
  Vec3 firstMoment = Vec3::Zero();   // m^4, about the reference point
  Mat3 secondMoment = Mat3::Zero();  // m^5, integral of x x^T about it
};

VolumeIntegrals IntegrateVolume(const Hull& hull, const Vec3& reference) {
  VolumeIntegrals sum;
  const auto vertices = hull.Vertices();
  const auto edges = hull.HalfEdges();
  for (const HullFace& face : hull.Faces()) {
    // Fan the face from its entry half-edge's origin.
    const HullHalfEdge& entry = edges[static_cast<std::size_t>(face.edge)];
    const Vec3 p = vertices[static_cast<std::size_t>(entry.origin)] - reference;
    int h = entry.next;
    int hNext = edges[static_cast<std::size_t>(h)].next;
    while (hNext != face.edge) {
      const Vec3 q =
          vertices[static_cast<std::size_t>(edges[static_cast<std::size_t>(h)].origin)] - reference;
      const Vec3 s =
          vertices[static_cast<std::size_t>(edges[static_cast<std::size_t>(hNext)].origin)] - reference;
      const double det = p.dot(q.cross(s));
      const Vec3 total = p + q + s;
      sum.volume += det / 6.0;
      sum.firstMoment += (det / 24.0) * total;
      sum.secondMoment += (det / 120.0) * (p * p.transpose() + q * q.transpose() + s * s.transpose() +
                                           total * total.transpose());
      h = hNext;
      hNext = edges[static_cast<std::size_t>(h)].next;
    }
  }
  return sum;
}

Vec3 VertexAverage(const Hull& hull) {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& v : hull.Vertices()) sum += v;
  return sum / static_cast<double>(hull.VertexCount());
}

}  // namespace

Result<MassProperties> ComputeMassProperties(const Hull& hull, double density) {
  if (!std::isfinite(density) || !(density > 0.0)) {
    return Error{"density must be finite and > 0 kg/m^3, got " + std::to_string(density)};
  }
  const Vec3 reference = VertexAverage(hull);
  const VolumeIntegrals integrals = IntegrateVolume(hull, reference);
  // A validated Hull is a closed convex solid with non-zero face areas, so
  // its volume is positive in exact arithmetic; but a volume is a product of
  // three lengths and the fifth power of a length is in the inertia, which
  // leave the double range for hulls the builder accepts (up to 1e150 m,
  // down to 1e-140 m): refused with the figures rather than inf or 0.
  if (!std::isfinite(integrals.volume) || !(integrals.volume > 0.0)) {
    return Error{"the hull's volume (" + std::to_string(integrals.volume) +
                 " m^3) is out of the double range: the hull is too large or too small for mass properties"};
  }

  const Vec3 localCenter = integrals.firstMoment / integrals.volume;
  const Mat3 centralMoment =
      integrals.secondMoment - integrals.volume * (localCenter * localCenter.transpose());
  Mat3 inertia = density * (centralMoment.trace() * Mat3::Identity() - centralMoment);
  // Symmetric in exact arithmetic; Eigen's vectorised sums may round the
  // two triangles differently, so mirror the average to make it exact.
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      const double average = 0.5 * (inertia(i, j) + inertia(j, i));
      inertia(i, j) = average;
      inertia(j, i) = average;
    }
  }

  if (!std::isfinite(density * integrals.volume) || !inertia.allFinite() || !localCenter.allFinite()) {
    return Error{"the mass (" + std::to_string(density * integrals.volume) +
                 " kg) or inertia of the hull is out of the double range: the hull is too large, or the "
                 "density too high, for mass properties"};
  }

  MassProperties props;
  props.volume = integrals.volume;
  props.mass = density * integrals.volume;
  props.centerOfMass = reference + localCenter;
  props.inertia = inertia;
  return props;
}

}  // namespace talus
