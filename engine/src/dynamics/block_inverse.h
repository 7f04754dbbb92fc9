// The pseudo-inverse of a contact pair's normal block K = J M^-1 J^T (2-4
// rows), which the block solve multiplies by the rows' velocity errors to
// get the least-norm impulse change (dynamics/contact_solver.h).
//
// Structure used. Row i of J is affine in the projection of point i on the
// contact plane (the component along n drops out of r x n). Two points, or
// three not on a line, give a full-rank K; four points of a plane always
// have an affine dependency c (sum c_i = 0, sum c_i p_i = 0 in the plane), so
// c^T J = 0 and K has rank 3 with null vector u = c / |c|. Then
//   K+ = (K + s u u^T)^-1 - u u^T / s   for any s > 0
// (u u^T / s inverts the added part on the null space; on its complement the
// sum is K), so every case is a closed-form 2x2, 3x3 or 4x4 inverse.
//
// Invariants: the result is symmetric, zero outside the leading count x
// count block, and equal (up to round-off) to the pseudo-inverse from an
// eigen decomposition of K padded to 4x4 with the identity that drops
// eigenvalues below 1e-9 of the largest (the solver's original, so below
// four points the cut is 1e-9 max(lambda_max, 1)), which stays as the
// fallback for blocks the closed form does not trust: collinear or nearly
// coincident points, anything within a factor 100 of that cut.
#pragma once

#include <span>

#include "talus/math.h"

namespace talus {

/// Pseudo-inverse of the leading count x count block of the symmetric
/// positive semi-definite `k` (count = arms.size(), 2 to 4), zero outside
/// it. `normal`: the pair's unit normal; `arms`: rA_i x n of each point
/// (metres), which locate the points in the contact plane.
Eigen::Matrix4d BlockPseudoInverse(const Eigen::Matrix4d& k, const Vec3& normal, std::span<const Vec3> arms);

/// The oracle: the same pseudo-inverse from a 4x4 SelfAdjointEigenSolver,
/// eigenvalues below 1e-9 of the largest taken as zero. Entries outside the
/// leading `count` x `count` block of `k` must be those of the identity.
Eigen::Matrix4d EigenPseudoInverse(const Eigen::Matrix4d& k, int count);

}  // namespace talus
