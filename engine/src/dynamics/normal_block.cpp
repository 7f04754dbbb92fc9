// The normal block's pseudo-inverse: the closed form where it is provably
// well conditioned, the eigen decomposition elsewhere (the derivation and
// the acceptance rule are in dynamics/normal_block.h).
#include "dynamics/normal_block.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/Eigenvalues>

#include "dynamics/spd_inverse.h"

namespace talus {
namespace {

// The eigen path's rank threshold, relative to the largest eigenvalue.
constexpr double kRankThreshold = 1e-9;

// Whether the inverse `inverse` of a matrix whose largest eigenvalue is at
// most `largestBound` has every eigenvalue above kRankThreshold times that
// bound: 1 / ||M^-1||_F is a lower bound of M's least eigenvalue.
template <class Matrix>
bool WellConditioned(const Matrix& inverse, double largestBound) {
  if (!inverse.allFinite()) return false;
  const double norm = inverse.norm();
  return norm > 0.0 && 1.0 / norm > kRankThreshold * largestBound;
}

// The combination z of four points' rows with sum z_i = 0 and
// sum z_i a_i = 0, normalised; nullopt when the arms are collinear or
// coincident (no unique z: K has rank 2 or less).
std::optional<Eigen::Vector4d> FourPointNullVector(const NormalArms& arms) {
  const Vec3 u1 = arms[1] - arms[0];
  const Vec3 u2 = arms[2] - arms[0];
  const Vec3 u3 = arms[3] - arms[0];
  // In a plane, (u2 x u3) u1 + (u3 x u1) u2 + (u1 x u2) u3 = 0, each cross
  // product a multiple of the plane's normal: read them along the largest.
  const Vec3 cross[3] = {u2.cross(u3), u3.cross(u1), u1.cross(u2)};
  int largest = 0;
  for (int i = 1; i < 3; ++i) {
    if (cross[i].squaredNorm() > cross[largest].squaredNorm()) largest = i;
  }
  const double length = cross[largest].norm();
  const double scale = std::max({u1.squaredNorm(), u2.squaredNorm(), u3.squaredNorm()});
  // Cross products at round-off of the arms' squared length: collinear.
  if (!(length > 1e-12 * scale)) return std::nullopt;
  const Vec3 axis = cross[largest] / length;
  Eigen::Vector4d z;
  z[1] = cross[0].dot(axis);
  z[2] = cross[1].dot(axis);
  z[3] = cross[2].dot(axis);
  z[0] = -(z[1] + z[2] + z[3]);
  return z.normalized();
}

// The closed form of the header, or nullopt where it is not provably the
// eigen path's answer.
std::optional<Eigen::Matrix4d> ClosedFormPseudoInverse(const Eigen::Matrix4d& k, int count,
                                                       const NormalArms& arms) {
  Eigen::Matrix4d result = Eigen::Matrix4d::Zero();
  // The identity padding of K is one of its eigenvalues (1) in the eigen
  // path's threshold, so it joins the bound here.
  if (count == 2) {
    const Eigen::Matrix2d inverse = SpdInverse<2>(k.topLeftCorner<2, 2>());
    if (!WellConditioned(inverse, std::max(k.topLeftCorner<2, 2>().trace(), 1.0))) return std::nullopt;
    result.topLeftCorner<2, 2>() = inverse;
    return result;
  }
  if (count == 3) {
    const Eigen::Matrix3d inverse = SpdInverse<3>(k.topLeftCorner<3, 3>());
    if (!WellConditioned(inverse, std::max(k.topLeftCorner<3, 3>().trace(), 1.0))) return std::nullopt;
    result.topLeftCorner<3, 3>() = inverse;
    return result;
  }
  if (count != 4) return std::nullopt;
  const std::optional<Eigen::Vector4d> z = FourPointNullVector(arms);
  if (!z) return std::nullopt;
  const double trace = k.trace();
  if (!(trace > 0.0)) return std::nullopt;
  // Any s > 0 works; K's scale keeps M's eigenvalue along z beside K's.
  const double s = trace / 4.0;
  const Eigen::Matrix4d zz = *z * z->transpose();
  const Eigen::Matrix4d inverse = SpdInverse<4>(k + s * zz);
  if (!WellConditioned(inverse, trace)) return std::nullopt;
  // K z is round-off only if z really is K's null vector (the rows were
  // built from these arms): checked, so a caller's inconsistent arms fall
  // back instead of giving a wrong inverse.
  if (!((k * *z).norm() <= 1e-12 * trace)) return std::nullopt;
  return inverse - zz / s;
}

}  // namespace

Eigen::Matrix4d EigenBlockPseudoInverse(const Eigen::Matrix4d& k, int count) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(k);
  const Eigen::Vector4d values = eigen.eigenvalues();
  const double largest = values.cwiseAbs().maxCoeff();
  Eigen::Vector4d inverse = Eigen::Vector4d::Zero();
  for (int i = 0; i < 4; ++i) {
    if (values[i] > kRankThreshold * largest) inverse[i] = 1.0 / values[i];
  }
  Eigen::Matrix4d blockInverse =
      eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
  for (int i = count; i < 4; ++i) {
    blockInverse.row(i).setZero();
    blockInverse.col(i).setZero();
  }
  return blockInverse;
}

Eigen::Matrix4d BlockPseudoInverse(const Eigen::Matrix4d& k, int count, const NormalArms& arms) {
  if (std::optional<Eigen::Matrix4d> closed = ClosedFormPseudoInverse(k, count, arms)) return *closed;
  return EigenBlockPseudoInverse(k, count);
}

}  // namespace talus
