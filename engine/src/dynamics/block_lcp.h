// The small linear complementarity problem of one contact pair's normal
// rows (2 to 4 points), solved exactly by enumerating which points push.
//
// The block solver (dynamics/contact_solver_sweep.cpp) first tries the
// unconstrained step dlambda = K+ (target - J v); when that would leave a
// point pulling (lambda + dlambda < 0) it used to fall back to one
// Gauss-Seidel pass row by row. That switch is discontinuous: an impulse a
// hair below zero gives a different answer than one a hair above, so
// round-off in K or v (1e-14) redrew a large pyramid's drift (issue 12).
// The exact solution of the LCP is a continuous, piecewise-linear function
// of its data (K is positive definite on every subset of points that spans
// a proper contact patch), so the pair's impulses no longer jump.
#pragma once

#include <Eigen/Core>

namespace talus {

/// Finds x >= 0 with w = K x - b >= 0 and x_i w_i = 0 for the first `count`
/// (1..4) entries (Murty's formulation: x the new accumulated impulses, w
/// the separating speeds above target). Tries every subset S of pushing
/// points (15 at most), solving K_SS x_S = b_S by LDLT; a subset qualifies
/// when x_S >= 0 and w outside S >= -tolerance, where tolerance = 1e-12 *
/// max(|b|_inf, |K|_inf |x|_inf) (round-off of the products, not physics).
/// Of the qualifying answers the least-norm one is taken (ties: the first
/// in a fixed order, largest subsets first), which is unique when K is
/// positive definite and continuous in the data when four coplanar points
/// make K singular. Entries at and past `count` of x are 0. Returns
/// false (x unspecified) when no subset qualifies: a singular K block
/// (collinear or repeated points), which the caller solves row by row.
bool SolveBlockLcp(const Eigen::Matrix4d& k, const Eigen::Vector4d& b, int count, Eigen::Vector4d& x);

}  // namespace talus
