// Mass properties of scenario bodies (see talus/reference/body_mass.h).
#include "talus/reference/body_mass.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace talus::reference {
namespace {

// Principal axes of a symmetric inertia tensor as a proper rotation (columns
// are the axes, ordered by Eigen's ascending eigenvalues, the third flipped
// when needed so the determinant is +1).
void Diagonalise(BodyMass& mass) {
  if (mass.inertia.isDiagonal(0.0)) {
    mass.principalRotation = Quat::Identity();
    mass.principalInertia = mass.inertia.diagonal();
    return;
  }
  Eigen::SelfAdjointEigenSolver<Mat3> solver(mass.inertia);
  Mat3 axes = solver.eigenvectors();
  if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);
  mass.principalRotation = Quat(axes).normalized();
  mass.principalInertia = solver.eigenvalues();
}

}  // namespace

SolidMoments ComputeSolidMoments(const PointHull& hull) {
  // Sum signed tetrahedra (origin, a, b, c): volume det/6, first moment
  // volume * (a + b + c) / 4, second moment (covariance) det/120 *
  // (sum v v^T + s s^T) with s = a + b + c.
  double volume = 0.0;
  Vec3 firstMoment = Vec3::Zero();
  Mat3 covariance = Mat3::Zero();
  for (const auto& triangle : hull.triangles) {
    const Vec3& a = hull.vertices[triangle[0]];
    const Vec3& b = hull.vertices[triangle[1]];
    const Vec3& c = hull.vertices[triangle[2]];
    const double det = a.dot(b.cross(c));
    const Vec3 sum = a + b + c;
    volume += det / 6.0;
    firstMoment += det / 24.0 * sum;
    covariance +=
        det / 120.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + sum * sum.transpose());
  }
  SolidMoments moments;
  moments.volume = volume;
  moments.centroid = firstMoment / volume;
  // Shift the covariance to the centroid, then I = trace(C) Id - C.
  const Mat3 centred = covariance - volume * moments.centroid * moments.centroid.transpose();
  moments.inertia = centred.trace() * Mat3::Identity() - centred;
  return moments;
}

Result<BodyMass> ComputeBodyMass(const harness::BodySpec& body) {
  BodyMass mass;
  Mat3 unitInertia = Mat3::Zero();  // inertia at density 1
  if (const auto* box = std::get_if<harness::BoxShape>(&body.shape)) {
    const Vec3 e = 2.0 * box->halfExtents;
    mass.volume = e.x() * e.y() * e.z();
    unitInertia.diagonal() =
        mass.volume / 12.0 *
        Vec3(e.y() * e.y() + e.z() * e.z(), e.x() * e.x() + e.z() * e.z(), e.x() * e.x() + e.y() * e.y());
  } else if (const auto* sphere = std::get_if<harness::SphereShape>(&body.shape)) {
    const double r = sphere->radius;
    mass.volume = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    unitInertia = 0.4 * mass.volume * r * r * Mat3::Identity();
  } else {
    const auto& points = std::get<harness::HullShape>(body.shape).points;
    auto hull = ComputePointHull(points);
    if (!hull) return Error{"body \"" + body.name + "\": " + hull.GetError().message};
    const SolidMoments moments = ComputeSolidMoments(hull.Value());
    mass.volume = moments.volume;
    mass.centroid = moments.centroid;
    unitInertia = moments.inertia;
  }
  if (body.motion == harness::Motion::Dynamic) {
    const double density = body.mass > 0.0 ? body.mass / mass.volume : body.density;
    mass.mass = density * mass.volume;
    mass.inertia = density * unitInertia;
    // Overflow (density 1e300 over a large body) or underflow must be a
    // refusal naming the body, not an inf or 0 that a peer turns into NaN.
    const double smallest = mass.inertia.diagonal().minCoeff();
    if (!std::isfinite(mass.mass) || !(mass.mass >= std::numeric_limits<double>::min())) {
      std::ostringstream problem;
      problem << "body \"" << body.name << "\": mass " << mass.mass << " kg (density " << density
              << " kg/m^3 over volume " << mass.volume << " m^3) is not a finite positive number";
      return Error{problem.str()};
    }
    if (!mass.inertia.allFinite() || !(smallest >= std::numeric_limits<double>::min())) {
      std::ostringstream problem;
      problem << "body \"" << body.name << "\": moment of inertia " << smallest << " kg m^2 (mass "
              << mass.mass << " kg) is not a finite positive number";
      return Error{problem.str()};
    }
  }
  Diagonalise(mass);
  return mass;
}

}  // namespace talus::reference
