// The per-step rows of the contact solver (ContactRowSet builds them; the
// derivations are in dynamics/contact_row_set.h): one header per touching
// pair, one normal row and two friction rows per point, cold per-point data
// apart. Shared by the scalar Sequential Impulses
// (sequential_impulse_sweeps.cpp, coupled_block_solver.cpp,
// shock_propagation.cpp, split_impulses.cpp) and the coloured wide
// solver (wide_contact_solver.{h,cpp}), which packs them into lanes.
#pragma once

#include "talus/math.h"

namespace talus {

// Below this tangential speed (m/s) the friction basis is a fixed function
// of the normal (AnyPerpendicular) instead of the sliding direction: a
// direction computed from round-off would only add noise. Both step
// solvers choose their tangents by it.
inline constexpr double kSlidingSpeed = 1e-9;

// A unit vector orthogonal to the unit `n`, from the world axis least
// aligned with it (deterministic and well conditioned). Both step solvers
// start their contact tangents from it, so they share one basis.
inline Vec3 AnyPerpendicular(const Vec3& n) {
  const Vec3 a = n.cwiseAbs();
  Vec3 axis = Vec3::UnitX();
  if (a.y() <= a.x() && a.y() <= a.z()) {
    axis = Vec3::UnitY();
  } else if (a.z() <= a.x() && a.z() <= a.y()) {
    axis = Vec3::UnitZ();
  }
  return n.cross(axis).normalized();
}

/// One row along direction d (the normal or a tangent) at one point: the
/// angular parts of J and their images under the inverse inertia.
struct RowJacobian {
  Vec3 angularA = Vec3::Zero();  ///< rA x d, metres
  Vec3 angularB = Vec3::Zero();  ///< rB x d, metres
  Vec3 imageA = Vec3::Zero();    ///< IA^-1 (rA x d), 1/(kg m); zero when A cannot move
  Vec3 imageB = Vec3::Zero();    ///< IB^-1 (rB x d), 1/(kg m); zero when B cannot move
};

/// The row along unit direction `d` at arms rA, rB (metres) of bodies with
/// these inverse inertias (world frame). Shared by the Sequential Impulses
/// rows and the soft step's.
inline RowJacobian MakeRowJacobian(const Vec3& d, const Vec3& rA, const Vec3& rB, const Mat3& invInertiaA,
                                   const Mat3& invInertiaB) {
  RowJacobian j;
  j.angularA = rA.cross(d);
  j.angularB = rB.cross(d);
  j.imageA = invInertiaA * j.angularA;
  j.imageB = invInertiaB * j.angularB;
  return j;
}

/// 1 / (J M^-1 J^T) of a row, the effective mass (kg); 0 when nothing can move.
inline double RowEffectiveMass(const RowJacobian& j, double invMassA, double invMassB) {
  const double k = invMassA + invMassB + j.angularA.dot(j.imageA) + j.angularB.dot(j.imageB);
  return k > 0.0 ? 1.0 / k : 0.0;
}

struct NormalRow {
  RowJacobian j;
  double mass = 0.0;     ///< kg, effective mass
  double target = 0.0;   ///< m/s, least normal separation speed
  double impulse = 0.0;  ///< N s, accumulated
};
// The hot records the sweeps stream every pass (docs/dynamics.md, "Solver
// data layout"): a normal row is 120 bytes, under two 64-byte cache lines,
// a friction row 112, so a point's three rows are 344 bytes (the wide
// solver's WidePoint is compared against this figure). Growing one is a
// choice to make on purpose.
static_assert(sizeof(RowJacobian) == 96, "RowJacobian: four Vec3, 96 bytes");
static_assert(sizeof(NormalRow) == 120, "NormalRow: 120 bytes, under two cache lines per point");

struct FrictionRow {
  RowJacobian j;
  double mass = 0.0;     ///< kg, effective mass
  double impulse = 0.0;  ///< N s, accumulated
};
static_assert(sizeof(FrictionRow) == 112, "FrictionRow: 112 bytes, under two cache lines per tangent");

/// Per point, read only by the split impulses, the timed bounces and the
/// wide solver's packing.
struct PointCold {
  double positionTarget = 0.0;  ///< m/s, split-impulse pseudo target
  double pseudoImpulse = 0.0;   ///< N s, accumulated split impulse
  /// The point bounces inside the step (BounceTiming::TimeOfImpact): its
  /// pseudo row is an equality that puts it on the reflected flight's end
  /// gap (the impulse may pull), and its impulses are not carried over.
  bool timedBounce = false;
  Vec3 armA = Vec3::Zero();  ///< rA = p - cA, world, metres (the wide solver's input)
  Vec3 armB = Vec3::Zero();  ///< rB = p - cB
};
// Cold: no sweep reads it, so it is kept out of the rows; 72 bytes, the
// budget of the split-impulse sweep and the wide packing that walk it.
static_assert(sizeof(PointCold) <= 72, "PointCold: 72 bytes, apart from the hot rows");

/// A friction impulse pattern of FrictionSolve::CoupledBlock as the sweep
/// reads it: the angular parts of its generalised row (sums of r x P over
/// the points). Their images under the inverse inertia are needed only to
/// build the operator, so they are not kept.
struct PatternRow {
  Vec3 angularA = Vec3::Zero();  ///< sum rA_i x P_i, metres
  Vec3 angularB = Vec3::Zero();  ///< sum rB_i x P_i, metres
};

/// FrictionSolve::CoupledBlock's per-step data of a pair with a normal block
/// (dynamics/coupled_block_solver.h): three friction impulse patterns as
/// generalised rows (slip along t1, along t2, spin about n), the pieces of
/// the block's solve operator, and the points' places in the contact plane.
/// 384 bytes, six cache lines (the sweep that tries every face pair is
/// bound by memory, not arithmetic), the flags in the padding at the end.
struct CoupledBlockRows {
  PatternRow pattern[3];
  /// B Knp: the normal block's pseudo-inverse times the normal-pattern coupling.
  Eigen::Matrix<double, 4, 3, Eigen::DontAlign> blockTimesCoupling = Eigen::Matrix<double, 4, 3>::Zero();
  /// Row i: point i's offset from the patterns' centre of pressure along
  /// t1 and t2, metres (where the accepted friction is shared out).
  Eigen::Matrix<double, 4, 2, Eigen::DontAlign> plane = Eigen::Matrix<double, 4, 2>::Zero();
  Eigen::Matrix3d schurInverse = Eigen::Matrix3d::Zero();  ///< (Kpp - Kpn B Knp)^-1
  bool spin = false;    ///< the spin pattern is used (some lever, some body can turn)
  bool usable = false;  ///< the Schur complement was positive definite
};
static_assert(sizeof(CoupledBlockRows) <= 384, "CoupledBlockRows: six cache lines, the sweep's budget");

struct PairRows {
  int bodyA = -1, bodyB = -1;  ///< solver-body indices
  int firstPoint = 0, pointCount = 0;
  /// Index into the friction rows: point 0's t1 row (t2 follows, then the
  /// next point's), or with manifoldFriction the manifold's rows
  /// (dynamics/manifold_friction.h).
  int firstFriction = 0;
  int block = -1;    ///< index into the block inverses, -1 when solved row by row
  int contact = -1;  ///< index into the contacts handed to Prepare
  Vec3 normal = Vec3::Zero();
  Vec3 tangent[2] = {Vec3::Zero(), Vec3::Zero()};
  double invMassA = 0.0, invMassB = 0.0;  ///< 1/kg; zero for bodies contacts cannot move
  double friction = 0.0;
  bool hasFriction = false;
  bool persisted = false;  ///< the pair touched last step (see Contact::persisted)
  /// Friction as the manifold's rows (FrictionSolve::PerManifold, and
  /// Adaptive's pairs outside loaded groups), not per point.
  bool manifoldFriction = false;
};
// Every pass over a pair reads its header first: 136 bytes, just over two
// cache lines, the flags in the tail padding (the wide solver's bundle
// header is compared against this figure, wide_contact_solver.h). The Mat3s and the block inverse it once
// carried (~450 bytes) live apart (docs/dynamics.md, "Compact headers").
static_assert(sizeof(PairRows) <= 136, "PairRows: 136 bytes, about two cache lines per pair");

}  // namespace talus
