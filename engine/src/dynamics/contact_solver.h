// ContactSolver: Sequential Impulses (projected Gauss-Seidel) on contact
// and friction constraints, section 3 of the write-up after Catto (GDC
// 2005-2009).
//
// Notation for one contact point p of the pair (A, B), normal n from B to A,
// rA = p - cA, rB = p - cB, relative velocity at p
//   dv = (vA + wA x rA) - (vB + wB x rB).
//
// Non-penetration. C = depth along n must not grow: Cdot = n . dv >= target.
//   Jacobian  J = [ n, rA x n, -n, -rB x n ]
//   Effective mass  m_n = 1 / (1/mA + 1/mB + (rA x n) . IA^-1 (rA x n)
//                                           + (rB x n) . IB^-1 (rB x n))
//   Impulse  dlambda = -m_n (n . dv - target); accumulated lambda clamped to
//   [0, inf) (contacts push, never pull), the body velocities changed by the
//   clamped difference along +n for A and -n for B.
//   target = beta/h max(depth - slop, 0) (Baumgarte bias, as written) for a
//   penetrating point; depth/h (< 0: the gap may close this step) for a
//   point not yet touching; max'ed with -e n.dv0 (restitution) when the
//   closing speed -n.dv0 exceeds the restitution threshold and the point
//   touches by the end of the step (depth - h n.dv0 > 0).
//
// Order. Each iteration sweeps all normal rows, then all friction rows.
//
// Block solve (option, default on). A pair's 2-4 normal rows are solved
//   together: dlambda = K+ (target - J v), K = J M^-1 J^T (4x4, rank 3 for
//   coplanar points, so its pseudo-inverse, from an eigen decomposition in
//   Prepare), accepted when every accumulated impulse stays >= 0, else row
//   by row. Box2D v2.4's two-point block solver extended to four points.
//
// Extra sweeps. In a step with new pairs (no impulses to warm start from)
//   the sweeps go on past the minimum until the new pairs' rows change by
//   less than a tolerance, up to a maximum.
//
// Friction. Cdot = t_k . dv = 0 for two tangents t1, t2 orthogonal to n
//   (t1 along the sliding velocity when there is one, so the sliding
//   direction gets the whole Coulomb bound).
//   Jacobian  J = [ t, rA x t, -t, -rB x t ],  m_t likewise with t for n.
//   Accumulated impulse clamped to [-mu lambda_n, mu lambda_n] with the
//   point's current lambda_n, re-read every time after the normal row moved.
//
// Position correction (WorldSettings::positionCorrection). Baumgarte (the
//   write-up's) is the bias in the velocity target above. Split impulses
//   move it to pseudo-velocities: the same normal row on (pv, pw) with
//   target beta/h max(depth - slop, 0), solved after the velocities and
//   added only to the position update, so position correction cannot add
//   kinetic energy. Non-linear Gauss-Seidel (an option; Catto's Box2D
//   v2.4 b2ContactSolver::SolvePositionConstraints, Jolt's position
//   solve) leaves the velocity target of a touching point at 0 and, after
//   the positions are integrated, sweeps the points again on positions:
//     each point keeps the surface points it started from on A and on B as
//     body-frame anchors; a sweep rebuilds them from the current poses,
//     depth d = (pB - pA) . n (n fixed for the step), C = clamp(beta (d -
//     positionSlop), 0, kMaxCorrection), and moves the bodies by the
//     impulse P = C m_n n (m_n at the current arms, inertia of the step's
//     start): cA += P / mA, qA turned by IA^-1 (rA x P), B the opposite.
//   Because the depth is re-measured after every move, a stack's contacts
//   agree on the positions instead of each fixing a stale depth, and no
//   velocity is left behind, so the slop can be 0.2 mm.
//
// Data: Prepare() builds one ContactRows header per touching pair and one
// PointRow per point in two dense vectors that keep their capacity between
// steps; the iterations walk those arrays and never allocate. Pairs where
// neither body can move under contact (static, kinematic, asleep) build no
// rows; mu == 0 builds no friction rows, e == 0 no restitution work.
#pragma once

#include <span>
#include <vector>

#include "dynamics/body_sim.h"
#include "dynamics/contact.h"
#include "talus/step_statistics.h"
#include "talus/world_settings.h"

namespace talus {

class ContactSolver {
 public:
  /// Builds the rows of `contacts` for a step of `h` seconds from the bodies'
  /// current velocities, loading the accumulated impulses (zero, or last
  /// step's when warm starting). Adds its counts to `stats`.
  void Prepare(std::span<const BodySim> bodies, std::span<const Contact> contacts,
               const WorldSettings& settings, double h, StepStatistics& stats);
  /// Applies the loaded impulses to the bodies (warm start).
  void WarmStart(std::span<BodySim> bodies) const;
  /// Runs `minIterations` Gauss-Seidel sweeps over all rows, then, if some
  /// pair is new (not persisted), more while the last one changed a row of
  /// a new pair by more than `tolerance` (m/s), up to `maxIterations` sweeps
  /// in all. Returns the sweeps run.
  int SolveVelocities(std::span<BodySim> bodies, int minIterations, int maxIterations, double tolerance);
  /// Runs `iterations` sweeps of the split-impulse pseudo-velocity rows.
  void SolveSplitImpulses(std::span<BodySim> bodies, int iterations);
  /// Non-linear Gauss-Seidel on the bodies' poses after the position update:
  /// at most `iterations` sweeps, stopping after the first sweep that found
  /// no point deeper than 3 `slop`; `beta` in [0, 1], `slop` in metres.
  /// Refreshes the world inverse inertia of the bodies it turned. Returns the
  /// number of sweeps run.
  int SolveNonlinearPositions(std::span<BodySim> bodies, int iterations, double beta, double slop);
  /// Writes the accumulated impulses back for next step's warm start.
  void StoreImpulses(std::span<Contact> contacts) const;

  /// Number of point rows built by the last Prepare.
  [[nodiscard]] int PointCount() const { return static_cast<int>(m_points.size()); }

 private:
  struct PointRow {
    Vec3 rA = Vec3::Zero();   ///< metres, from A's centre of mass
    Vec3 rB = Vec3::Zero();   ///< metres, from B's centre of mass
    double normalMass = 0.0;  ///< kg
    double tangentMass[2] = {0.0, 0.0};
    double target = 0.0;          ///< m/s, least normal separation speed
    double positionTarget = 0.0;  ///< m/s, split-impulse pseudo target
    double normalImpulse = 0.0;   ///< N s, accumulated
    double tangentImpulse[2] = {0.0, 0.0};
    double pseudoImpulse = 0.0;
    Vec3 localAnchorA = Vec3::Zero();  ///< A's surface point, A's axes, from its centre of mass
    Vec3 localAnchorB = Vec3::Zero();  ///< B's surface point, B's axes, from its centre of mass
  };
  struct PairRows {
    int contact = -1;  ///< index into the contacts handed to Prepare
    int bodyA = -1, bodyB = -1;
    int firstPoint = 0, pointCount = 0;
    Vec3 normal = Vec3::Zero();
    Vec3 tangent[2] = {Vec3::Zero(), Vec3::Zero()};
    double friction = 0.0;
    bool hasFriction = false;
    double invMassA = 0.0, invMassB = 0.0;
    Mat3 invInertiaA = Mat3::Zero();  ///< world axes; zero for bodies contacts cannot move
    Mat3 invInertiaB = Mat3::Zero();
    bool block = false;      ///< normal rows solved together through blockInverse
    bool persisted = false;  ///< the pair touched last step (see Contact::persisted)
    Eigen::Matrix4d blockInverse = Eigen::Matrix4d::Zero();
  };

  void SolveNormals(std::span<BodySim> bodies, const PairRows& pair);
  bool SolveNormalBlock(std::span<BodySim> bodies, const PairRows& pair);
  void PrepareBlock(PairRows& pair) const;
  /// Records the velocity change (impulse / mass) of a row of a new pair.
  void NoteChange(const PairRows& pair, double impulse, double mass);
  void SolveFriction(std::span<BodySim> bodies, const PairRows& pair);

  std::vector<PairRows> m_pairs;
  std::vector<PointRow> m_points;
  std::vector<int> m_newPairs;   ///< indices into m_pairs of pairs that did not persist
  double m_largestChange = 0.0;  ///< m/s, the largest row velocity change of this sweep
};

}  // namespace talus
