// Closed-form pseudo-inverse of a contact pair's normal block, with the
// eigen decomposition as oracle and fallback; see dynamics/block_inverse.h.
#include "dynamics/block_inverse.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace talus {
namespace {

// Fast-path acceptance: det(M) > kWellConditioned trace(M)^(n-1) scale for
// the n x n matrix M inverted in closed form. Since lambda_max <= trace and
// lambda_min >= det / lambda_max^(n-1), it guarantees lambda_min >
// kWellConditioned scale, 100 times the eigen path's rank cut (1e-9 scale),
// so both keep every eigenvalue and agree up to round-off; anything closer
// to singular (collinear or nearly coincident points) takes the eigen path.
constexpr double kWellConditioned = 1e-7;

// A null vector of K for four contact points, unit length, or zero when the
// points are (nearly) collinear: the affine dependency of the arms a_i =
// rA_i x n (the points' projections on the contact plane turned by 90
// degrees). With d_i = a_i - a_0, the 2D identity [d2 d3] d1 + [d3 d1] d2 +
// [d1 d2] d3 = 0 gives c_1..c_3 as the cross products n.(d_j x d_k).
Eigen::Vector4d AffineDependency(const Vec3& n, std::span<const Vec3> a) {
  const Vec3 d1 = a[1] - a[0], d2 = a[2] - a[0], d3 = a[3] - a[0];
  const double c1 = n.dot(d2.cross(d3));
  const double c2 = n.dot(d3.cross(d1));
  const double c3 = n.dot(d1.cross(d2));
  const Eigen::Vector4d c(-(c1 + c2 + c3), c1, c2, c3);
  const double size = std::max({d1.squaredNorm(), d2.squaredNorm(), d3.squaredNorm()});
  // The cross products are areas; much smaller than the spread squared,
  // their direction is round-off.
  if (!(c.norm() > 1e-6 * size)) return Eigen::Vector4d::Zero();
  return c.normalized();
}

// Closed-form inverse of the leading n x n block of `m` into `out`, when it
// passes the conditioning test against `scale` (the largest eigenvalue the
// eigen path measures its cut against, or a bound on it); false otherwise.
template <int kN>
bool InvertWellConditioned(const Eigen::Matrix4d& m, double scale, Eigen::Matrix4d& out) {
  const Eigen::Matrix<double, kN, kN> block = m.topLeftCorner<kN, kN>();
  const double trace = block.trace();
  if (!(block.determinant() > kWellConditioned * std::pow(trace, kN - 1) * scale)) return false;
  out.setZero();
  out.topLeftCorner<kN, kN>() = block.inverse();
  return true;
}

}  // namespace

Eigen::Matrix4d EigenPseudoInverse(const Eigen::Matrix4d& k, int count) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(k);
  const Eigen::Vector4d values = eigen.eigenvalues();
  const double largest = values.cwiseAbs().maxCoeff();
  Eigen::Vector4d inverse = Eigen::Vector4d::Zero();
  for (int i = 0; i < 4; ++i) {
    if (values[i] > 1e-9 * largest) inverse[i] = 1.0 / values[i];
  }
  Eigen::Matrix4d result = eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
  for (int i = count; i < 4; ++i) {
    result.row(i).setZero();
    result.col(i).setZero();
  }
  return result;
}

Eigen::Matrix4d BlockPseudoInverse(const Eigen::Matrix4d& k, const Vec3& normal, std::span<const Vec3> arms) {
  const int count = static_cast<int>(arms.size());
  assert(count >= 2 && count <= 4);
  Eigen::Matrix4d result;
  // Below four points the eigen path sees K padded with the identity, so its
  // cut is 1e-9 max(lambda_max(K), 1): heavy bodies (K ~ 1e-3 kg^-1 for the
  // pyramid's 8 t cubes) drop a near-singular mode (two points a millimetre
  // apart) that a relative test would keep. The closed form keeps that cut.
  double trace = 0.0;
  for (int i = 0; i < count; ++i) trace += k(i, i);
  const double padded = std::max(trace, 1.0);
  if (count == 2 && InvertWellConditioned<2>(k, padded, result)) return result;
  if (count == 3 && InvertWellConditioned<3>(k, padded, result)) return result;
  if (count == 4) {
    const Eigen::Vector4d u = AffineDependency(normal, arms);
    // Any s > 0 is exact; the mean diagonal keeps the sum's eigenvalues of
    // one scale, so the conditioning test judges K's own three.
    const double s = 0.25 * k.trace();
    const Eigen::Matrix4d deflated = k + s * u * u.transpose();
    if (u.squaredNorm() > 0.0 && InvertWellConditioned<4>(deflated, deflated.trace(), result)) {
      return result - (u * u.transpose()) / s;
    }
  }
  return EigenPseudoInverse(k, count);
}

}  // namespace talus
