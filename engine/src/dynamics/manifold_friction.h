// FrictionSolve::PerManifold (and Adaptive's lightly loaded pairs): a pair's
// friction as three rows of the whole manifold instead of two rows per point
// (the form Gregorius's manifold friction, Jolt and Box3D's predecessors
// use; docs/dynamics.md, "Friction per manifold").
//
// Rows (at PairRows::firstFriction, ManifoldFrictionRowCount of them):
//   0, 1  slip along t1 and t2 at the pair's centre of pressure p, the
//         points weighted by the normal impulses the step starts from
//         (w_i = lambda_i / sum lambda, equal weights when there are none):
//         J = [ t, (p - cA) x t, -t, -(p - cB) x t ];
//   2     spin about n (pairs of two or more points): J = [ 0, n, 0, -n ],
//         m = 1 / (n.IA^-1 n + n.IB^-1 n).
// Why the centre of pressure: per-point friction that slips the same way
// at every point adds up to a force through p, so a slip row placed
// anywhere else also twists the body about n by (x - p) x F at every
// application, and the spin row must take that back sweep after sweep.
// Measured: an arch of wedge blocks whose joints carry their thrust near
// one edge fell in 17 of 17 round-off draws with the rows at the mean of
// the points and stood in 17 of 17 at p (docs/dynamics.md).
// Bounds, from the points' current normal impulses lambda_i:
//   slip  |(lambda_1, lambda_2)| <= mu sum lambda_i, a disc (the Coulomb
//         cone is round; the per-point rows clamp each tangent alone, a
//         square);
//   spin  |lambda_s| <= mu sum lambda_i |d_i|, d_i the point's offset from
//         the mean c of the points in the contact plane: the most torque
//         the points' own Coulomb bounds can give when the pair only spins
//         about c, so a spinning box stops as it does with per-point rows.
//         A pair that slides and spins at once gets each bound in full,
//         where per-point friction shares one bound between the two: the
//         manifold rows brake such a pair harder (measured in
//         docs/dynamics.md).
// The two slip rows are solved from the same velocities and their sum
// projected onto the disc; the spin row follows.
//
// Warm start. The Contact keeps friction per point (a world vector per
// point, as PerPoint stores it), so the warm start survives manifold
// changes, feature matching and a switch of FrictionSolve. The manifold's
// impulses are written as f_i = w_i F + lambda_s (n x d_i) / sum |d_j|^2,
// with the weights w_i of the normal impulses stored beside them: their sum
// is F, and their moment is F's at that centre of pressure plus lambda_s
// about n (because sum w_i d_i = p - c and sum d_i = 0). The next step's
// rows are weighted by those same normal impulses, so reading back gives F
// and lambda_s exactly. The vectors are the impulses that moved the bodies
// up to the twist about n of F between the step's starting and final
// centres of pressure. Stored with the starting weights instead, the
// vectors would be exact and the read-back's spin off by that twist:
// measured, the arch that stands in 17 of 17 draws this way fell in 10 of
// 17 that way, the spin row's warm start carrying the twist of a joint
// whose pressure moves.

#pragma once

#include <algorithm>
#include <cmath>
#include <span>

#include "dynamics/contact_rows.h"
#include "dynamics/pair_velocities.h"
#include "talus/math.h"

namespace talus {

/// Rows of a pair with `pointCount` points under PerManifold: two slip
/// rows, and the spin row when there are two or more points.
inline int ManifoldFrictionRowCount(int pointCount) { return pointCount >= 2 ? 3 : 2; }

/// The offsets d_i of points from their mean, in the plane normal to the
/// unit `n` (metres); `points` yields point i's position (or any vector
/// that differs from it by one constant, such as its arm from a body's
/// centre). Returns the mean.
template <typename PointOf>
Vec3 ManifoldOffsets(int count, const Vec3& n, PointOf points, std::span<Vec3> offsets) {
  Vec3 centre = Vec3::Zero();
  for (int i = 0; i < count; ++i) centre += points(i);
  centre /= static_cast<double>(count);
  for (int i = 0; i < count; ++i) {
    const Vec3 d = points(i) - centre;
    offsets[static_cast<std::size_t>(i)] = d - n * n.dot(d);
  }
  return centre;
}

/// The slip rows' weights w_i of a manifold's points (they sum to 1): each
/// point's share of `normalImpulses` (N s, >= 0) when they add up to more
/// than zero, else equal shares. Returns the weighted mean of `points`
/// (the centre of pressure; `points` as in ManifoldOffsets).
template <typename PointOf>
Vec3 ManifoldSlipShares(int count, std::span<const double> normalImpulses, PointOf points,
                        std::span<double> shares) {
  double total = 0.0;
  for (int i = 0; i < count; ++i) total += normalImpulses[static_cast<std::size_t>(i)];
  Vec3 centre = Vec3::Zero();
  for (int i = 0; i < count; ++i) {
    const double w =
        total > 0.0 ? normalImpulses[static_cast<std::size_t>(i)] / total : 1.0 / static_cast<double>(count);
    shares[static_cast<std::size_t>(i)] = w;
    centre += w * points(i);
  }
  return centre;
}

/// A manifold's friction impulses: slip along the pair's t1, t2 (N s) and
/// spin about n (N m s).
struct ManifoldFrictionImpulses {
  double slip[2] = {0.0, 0.0};
  double spin = 0.0;
};

/// The manifold impulses that per-point friction vectors `perPoint` add up
/// to with slip `shares`: their sum along each tangent, and their torque
/// along n about the mean less the slip's own about it at the centre of
/// pressure.
inline ManifoldFrictionImpulses SumManifoldFriction(std::span<const Vec3> perPoint,
                                                    std::span<const Vec3> offsets,
                                                    std::span<const double> shares, const Vec3& n,
                                                    const Vec3 (&tangent)[2]) {
  ManifoldFrictionImpulses sum;
  Vec3 total = Vec3::Zero();
  Vec3 pressureOffset = Vec3::Zero();
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    total += perPoint[i];
    pressureOffset += shares[i] * offsets[i];
    sum.spin += n.dot(offsets[i].cross(perPoint[i]));
  }
  sum.spin -= n.dot(pressureOffset.cross(total));
  sum.slip[0] = total.dot(tangent[0]);
  sum.slip[1] = total.dot(tangent[1]);
  return sum;
}

/// Per-point friction vectors that add up to `impulses` (see the header):
/// the slip in proportion to the slip `shares`, the spin as tangential
/// impulses in proportion to each point's offset. With all offsets zero the
/// spin is dropped (such a pair has no spin row).
inline void ShareManifoldFriction(const ManifoldFrictionImpulses& impulses, std::span<const Vec3> offsets,
                                  std::span<const double> shares, const Vec3& n, const Vec3 (&tangent)[2],
                                  std::span<Vec3> perPoint) {
  const Vec3 slip = impulses.slip[0] * tangent[0] + impulses.slip[1] * tangent[1];
  double spread = 0.0;
  for (const Vec3& d : offsets) spread += d.squaredNorm();
  const double spinShare = spread > 0.0 ? impulses.spin / spread : 0.0;
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    perPoint[i] = shares[i] * slip + spinShare * n.cross(offsets[i]);
  }
}

/// What a pair's manifold friction rows read of its normal rows: the
/// bounds' loads, from the points' current normal impulses.
struct ManifoldLoad {
  double load = 0.0;       ///< N s, sum of the normal impulses lambda_i
  double spinLoad = 0.0;   ///< N m s, sum of lambda_i |d_i|
  double meanLever = 0.0;  ///< m, mean of the |d_i|
};

/// The ManifoldLoad of a pair's `pointCount` (>= 1) normal rows `normals`,
/// `levers` the points' |d_i|.
inline ManifoldLoad SumManifoldLoad(int pointCount, const NormalRow* normals, const double* levers) {
  ManifoldLoad sum;
  for (int i = 0; i < pointCount; ++i) {
    sum.load += normals[i].impulse;
    sum.spinLoad += normals[i].impulse * levers[i];
    sum.meanLever += levers[i];
  }
  sum.meanLever /= static_cast<double>(pointCount);
  return sum;
}

/// One pass over a pair's manifold friction rows. `rows` are its
/// ManifoldFrictionRowCount rows, `loads` what its normal rows hold now
/// (SumManifoldLoad). The policy gives each row's effective mass
/// (`Mass(row, linear)`: linear is false for the spin row, which has no
/// linear part), applies an impulse (`Apply(v, delta, d, row)`, d zero for
/// the spin row) and notes the velocity change (`Note(change)`, m/s; the
/// spin row's at the mean lever). The sweeps and shock propagation (with a
/// held body) share it.
template <typename Policy>
void SolveManifoldFrictionRows(const PairRows& pair, const ManifoldLoad& loads, FrictionRow* rows,
                               PairVelocities& v, Policy& policy) {
  const double bound = pair.friction * loads.load;
  double mass[2];
  double next[2];
  for (int k = 0; k < 2; ++k) {
    mass[k] = policy.Mass(rows[k], true);
    next[k] = rows[k].impulse - mass[k] * v.Along(pair.tangent[k], rows[k].j);
  }
  // The disc clamp compares squared lengths and takes the root only when it
  // clamps: std::hypot's overflow-safe scaling was measured a large share of
  // a pyramid step (docs/bench-scenes.md, "the disc clamp"), and impulses are
  // nowhere near the range where squares overflow.
  const double squaredLength = next[0] * next[0] + next[1] * next[1];
  if (squaredLength > bound * bound) {
    const double scale = bound / std::sqrt(squaredLength);
    next[0] *= scale;
    next[1] *= scale;
  }
  for (int k = 0; k < 2; ++k) {
    const double delta = next[k] - rows[k].impulse;
    rows[k].impulse = next[k];
    if (mass[k] > 0.0) policy.Note(std::abs(delta) / mass[k]);
    policy.Apply(v, delta, pair.tangent[k], rows[k]);
  }
  if (pair.pointCount < 2) return;
  FrictionRow& spin = rows[2];
  const double spinMass = policy.Mass(spin, false);
  const double spinRate = spin.j.angularA.dot(v.wA) - spin.j.angularB.dot(v.wB);
  const double spinBound = pair.friction * loads.spinLoad;
  const double old = spin.impulse;
  spin.impulse = std::clamp(old - spinMass * spinRate, -spinBound, spinBound);
  const double delta = spin.impulse - old;
  if (spinMass > 0.0) policy.Note(std::abs(delta) / spinMass * loads.meanLever);
  policy.Apply(v, delta, Vec3::Zero(), spin);
}

}  // namespace talus
