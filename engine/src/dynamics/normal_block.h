// The normal block of a pair: K = J M^-1 J^T over a pair's 2 to 4 normal
// rows and its pseudo-inverse, which the block solves of the sweeps, the
// coupled friction block, shock propagation and the soft step apply.
//
// Why a pseudo-inverse. The normal row of point i is [n, a_i, -n, -b_i]
// with a_i = rA_i x n and b_i = rB_i x n. Every a_i lies in the plane
// orthogonal to n, and four vectors in a plane always admit a combination
// z with sum z_i = 0 and sum z_i a_i = 0 (four unknowns, three equations).
// Since b_i - a_i = (cA - cB) x n is the same for every point, the same z
// cancels the b_i too: J^T z = 0, so a four-point K is singular (rank 3)
// for every manifold, coplanar or not. The least-norm solution K+ r shares
// the load evenly among the points where any solution would do.
//
// How it is computed (BlockPseudoInverse). The closed form first:
//   * 2 or 3 points: K is generically regular, K+ = K^-1;
//   * 4 points: z from the arms (the cross products of a_i - a_0, which
//     are all parallel to n), normalised; with s > 0,
//     (K + s z z^T)^-1 = K+ + z z^T / s, so K+ = (K + s z z^T)^-1 - z z^T / s.
// Each is accepted only when the inverse it took is provably well
// conditioned: 1 / ||M^-1||_F (a lower bound of M's least eigenvalue)
// above 1e-9 times an upper bound of the eigen path's largest eigenvalue,
// trace(K) for four points and max(trace(K), 1) below four (the identity
// padding's eigenvalue 1 is among the eigen path's). Otherwise
// (collinear or coincident points, a body nothing moves) the eigen
// decomposition of K decides the rank, its eigenvalues below 1e-9 of the
// largest counted as zero. An accepted closed form is then the answer the
// eigen decomposition gives, to round-off: every eigenvalue it inverted is
// above the eigen path's threshold, and z's is at round-off. The cost
// measured either way is in docs/dynamics.md, "Normal block: the closed
// form".
#pragma once

#include <array>

#include <Eigen/Core>

#include "dynamics/contact_rows.h"
#include "talus/math.h"

namespace talus {

/// A pair's normal block K = J M^-1 J^T over its `count` points, the
/// identity past them; `jacobian(i)` is point i's normal RowJacobian.
/// Shared by the Sequential Impulses rows and the soft step's rows (shock
/// propagation leaves a held body's terms out, so builds its own).
template <class JacobianOf>
Eigen::Matrix4d NormalBlock(int count, double invMassA, double invMassB, JacobianOf jacobian) {
  Eigen::Matrix4d k = Eigen::Matrix4d::Identity();
  for (int i = 0; i < count; ++i) {
    for (int j = 0; j < count; ++j) {
      const RowJacobian& ji = jacobian(i);
      const RowJacobian& jj = jacobian(j);
      k(i, j) = invMassA + invMassB + ji.angularA.dot(jj.imageA) + ji.angularB.dot(jj.imageB);
    }
  }
  return k;
}

/// The angular parts rA_i x n of a pair's normal rows, points past the
/// count unread: what the four-point closed form needs besides K.
using NormalArms = std::array<Vec3, 4>;

/// The arms of a pair's `count` points; `jacobian(i)` is point i's normal
/// RowJacobian, as for NormalBlock.
template <class JacobianOf>
NormalArms NormalArmsOf(int count, JacobianOf jacobian) {
  NormalArms arms{};
  for (int i = 0; i < count; ++i) arms[static_cast<std::size_t>(i)] = jacobian(i).angularA;
  return arms;
}

/// The pseudo-inverse of a pair's normal block K over `count` points
/// (padded with the identity past them, as NormalBlock builds it): the
/// closed form above where it is well conditioned, else from K's eigen
/// decomposition with eigenvalues below 1e-9 of the largest counted as
/// zero. Rows and columns past `count` are zero. `arms` are the points'
/// rA x n (any body's arms do: see the header comment).
Eigen::Matrix4d BlockPseudoInverse(const Eigen::Matrix4d& k, int count, const NormalArms& arms);

/// The eigen-decomposition path alone (the reference the closed form is
/// tested against, and its fallback).
Eigen::Matrix4d EigenBlockPseudoInverse(const Eigen::Matrix4d& k, int count);

}  // namespace talus
