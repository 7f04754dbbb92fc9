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
//   touches by the end of the step (depth - h n.dv0 > 0). That is
//   BounceTiming::StepBoundary; with TimeOfImpact (dynamics/bounce_timing.h)
//   a point that reaches the surface at t* in [-h, h] (from its gap, its
//   normal speed at the step's start and the normal acceleration forces
//   gave it, (n.dv0 - n.dv_start) / h) gets instead the reflected flight's
//   end speed as target, and a pseudo-velocity row with target
//   (g(h) + depth) / h - u(h), solved as an equality, moves it onto the
//   reflected flight's end gap g(h). A speculative point that closes faster
//   than the threshold but misses this step, on a body that moves exactly
//   under constant acceleration (TranslationIntegrator::
//   ExactConstantAcceleration), gets the target -gap/h + a h / 2 (the gap
//   its untouched flight closes), so the approach is not braked a step
//   early.
//
// Order. Each iteration sweeps all normal rows, then all friction rows.
//
// Block solve (option, default on). A pair's 2-4 normal rows are solved
//   together: dlambda = K+ (target - J v), K = J M^-1 J^T (4x4, rank 3 for
//   four coplanar points, so its pseudo-inverse, from an eigen decomposition
//   in Prepare), accepted when every accumulated impulse stays >= 0, else
//   row by row. Box2D v2.4's two-point block solver extended to four points.
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
// Joint block (FrictionSolve::CoupledBlock, the default; face contacts of 3-4
//   points with a normal block). With weights
//   w_i = lambda_n,i / sum lambda_n, three friction impulse patterns over the
//   pair's points: P1_i = w_i t1, P2_i = w_i t2 (a force through the centre
//   of pressure c) and P3_i = lambda_n,i (n x (p_i - c)) / S,
//   S = sum lambda_n,i |n x (p_i - c)|^2 (a unit torque about n through c,
//   no net force). Each is a generalised row
//   J_p = [F_p, sum rA_i x P_p,i, -F_p, -sum rB_i x P_p,i]. The pair's normal
//   rows and the three patterns are solved as one system K x = r (targets
//   for the normals, zero slip and spin for the patterns), through the
//   Schur complement of the normal block's pseudo-inverse. The friction's
//   new total force and moment about n are then shared among the points in
//   proportion to the new normal impulses (for points in the contact plane
//   that moves nothing), and the block is accepted when every normal
//   impulse stays >= 0 and every point's friction inside
//   [-mu lambda_n, mu lambda_n] per tangent; the pair's friction rows are
//   then skipped in that sweep. Otherwise (sliding, lifting) the normal
//   block and the per-point friction rows run as usual, and the block is
//   not tried again that step.
//
// Position correction (MethodSettings::positionCorrection). Baumgarte (the
//   write-up's) is the bias in the velocity target above. Split impulses
//   move it to pseudo-velocities: the same normal row on (pv, pw) with
//   target beta/h max(depth - slop, 0), solved after the velocities and
//   added only to the position update, so position correction cannot add
//   kinetic energy. (Non-linear Gauss-Seidel position sweeps were measured
//   and retired: docs/dynamics.md, "Retired options".)
//
// Data (the layout the sweeps walk; see docs/dynamics.md). Prepare()
//   gathers the velocities of every body a row touches into SolverBodies
//   (48 bytes each; bodies contacts cannot move keep zero inverse mass and
//   inertia there, so the sweep needs no branch and never writes them) and
//   builds, in dense vectors that keep their capacity between steps:
//   * one PairRows header per touching pair (solver-body indices, normal,
//     tangents, inverse masses, friction, flags);
//   * one NormalRow per point and two FrictionRows per point (one per
//     tangent), each with its Jacobian's angular parts r x d precomputed
//     together with their images under the inverse inertia, IA^-1 (rA x d)
//     and IB^-1 (rB x d). A row is then
//       Cdot = d.(vA - vB) + (rA x d).wA - (rB x d).wB     (two dot products)
//       vA += mA^-1 dl d, wA += dl IA^-1 (rA x d), B the opposite (axpys),
//     no cross product and no matrix product inside the sweep;
//   * cold per-point data (split-impulse target and impulse, arms) and the block pseudo-inverses apart.
//   The iterations never allocate. After the sweeps Scatter() writes the
//   solver bodies' velocities back. Pairs where neither body can move under
//   contact (static, kinematic, asleep) build no rows; mu == 0 builds no
//   friction rows, e == 0 no restitution work.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "dynamics/body_sim.h"
#include "dynamics/contact.h"
#include "dynamics/contact_rows.h"
#include "dynamics/solver_body.h"
#include "dynamics/wide_contact_solver.h"
#include "jobs/job_pool.h"
#include "talus/step_statistics.h"
#include "talus/world_settings.h"

namespace talus {

struct PairVelocities;

/// Which bodies of a pair shock propagation moves (contact_solver_shock.cpp):
/// their inverse masses, zero for the held one.
struct ShockSides {
  bool moveA = true;
  bool moveB = true;
  double invMassA = 0.0;
  double invMassB = 0.0;
};

class ContactSolver {
 public:
  /// How Prepare spreads its pairs and the coloured solver its colours'
  /// bundles over threads (jobs/job_pool.h: a chain of phases, each loop
  /// finished before the next starts); unset, every chunk runs in order on
  /// the caller's thread. Results do not depend on how a phase is cut or
  /// who runs it (tested): each pair writes only its own rows, and each
  /// bundle of a colour only its own rows and bodies.
  void SetPhaseRunner(PhaseRunner runner) { m_runner = std::move(runner); }

  /// Builds the rows of `contacts` for a step of `h` seconds and gathers the
  /// velocities of their bodies from `bodies` (the solver works on its own
  /// copy until Scatter), loading the accumulated impulses (zero, or last
  /// step's when warm starting). Adds its counts to `stats`.
  void Prepare(std::span<const BodySim> bodies, std::span<const Contact> contacts,
               const WorldSettings& settings, double h, StepStatistics& stats);
  /// Applies the loaded impulses to the gathered velocities (warm start).
  void WarmStart();
  /// Runs `minIterations` Gauss-Seidel sweeps over all rows, then, if some
  /// pair is new (not persisted), more while the last one changed a row of
  /// a new pair by more than `tolerance` (m/s), up to `maxIterations` sweeps
  /// in all. Returns the sweeps run.
  int SolveVelocities(int minIterations, int maxIterations, double tolerance);
  /// Shock propagation (MethodSettings::shockPropagation; derivation in
  /// contact_solver_shock.cpp): the pairs level by level from the
  /// immovable bodies up, each pair's lower body held, up to `maxSweeps`
  /// sweeps per level until a sweep changes no velocity by more than
  /// `tolerance` (m/s). Returns the sweeps run. SolveVelocities runs it last
  /// when the setting is on.
  int PropagateShock(int maxSweeps, double tolerance);
  /// Runs `iterations` sweeps of the split-impulse pseudo-velocity rows
  /// (and of the timed bounces' position rows).
  void SolveSplitImpulses(int iterations);
  /// Shock propagation's sweeps in the last SolveVelocities (0 when off).
  [[nodiscard]] int ShockSweeps() const { return m_shockSweeps; }
  /// Points of the last Prepare that bounce inside the step.
  [[nodiscard]] int TimedBounceCount() const { return m_timedBounces; }
  /// Whether this step's positions take pseudo velocities: split impulses
  /// were selected at the last Prepare, or some point bounces inside the
  /// step (its position row needs them whatever the position correction).
  /// Then SolveSplitImpulses runs, Scatter writes them and the position
  /// update adds them.
  [[nodiscard]] bool UsesPseudoVelocities() const { return m_split || m_timedBounces > 0; }
  /// Writes the solved velocities of the bodies contacts can move back to
  /// `bodies` (the array handed to Prepare), with `pseudo` the split-impulse
  /// pseudo velocities too. Bodies without rows are not touched.
  void Scatter(std::span<BodySim> bodies, bool pseudo) const;
  /// Writes the accumulated impulses back for next step's warm start.
  void StoreImpulses(std::span<Contact> contacts) const;

  /// Number of point rows built by the last Prepare.
  [[nodiscard]] int PointCount() const { return static_cast<int>(m_normals.size()); }
  /// The coloured solver of the last Prepare (empty unless ByColour).
  [[nodiscard]] const WideContactSolver& Wide() const { return m_wide; }

  /// FrictionSolve::CoupledBlock's tries in the last step's sweeps.
  struct JointBlockCounts {
    std::int64_t accepted = 0;  ///< the pair stuck: normals and friction solved as one block
    std::int64_t refused = 0;   ///< a pulling normal, a friction past its bound, or no lever for the twist
  };
  [[nodiscard]] const JointBlockCounts& LastJointBlockCounts() const { return m_jointCounts; }

 private:
  static RowJacobian MakeJacobian(const Vec3& d, const Vec3& rA, const Vec3& rB, const Mat3& invInertiaA,
                                  const Mat3& invInertiaB);
  /// 1 / (J M^-1 J^T) of a row (the effective mass), kg; 0 when nothing can move.
  static double RowMass(const RowJacobian& j, const PairRows& pair);
  /// Integer counts a pair's rows add to the step's statistics, summed per
  /// chunk of pairs (an integer sum: the same in any order).
  struct PrepareCounts {
    int timedBounces = 0;
    int restitutionSkipped = 0;
  };
  /// The rows of one pair whose header Prepare's serial pass filled (its
  /// bodies, row offsets, block slot): writes only that pair's rows, so
  /// pairs may be prepared on any thread in any order.
  void PreparePair(std::span<const BodySim> bodies, const Contact& contact, const WorldSettings& settings,
                   double h, PairRows& pair, PrepareCounts& counts);
  void PrepareBlock(PairRows& pair);
  /// The pseudo-inverse of a pair's normal block K (padded with the
  /// identity past `count` points): eigenvalues below 1e-9 of the largest
  /// count as zero, rows and columns past `count` zero.
  static Eigen::Matrix4d BlockPseudoInverse(const Eigen::Matrix4d& k, int count);
  template <bool kTrack>
  void SolveNormals(const PairRows& pair);
  template <bool kTrack>
  bool SolveNormalBlock(const PairRows& pair);
  template <bool kTrack>
  void SolveFriction(const PairRows& pair);
  /// Whether FrictionSolve::CoupledBlock applies to `pair`: selected, a
  /// normal block, friction, and at least three points (a face). Edge
  /// contacts (two points) keep the per-point rows: measured, the block on
  /// them changed how boxes tip over an edge (box_toss at 1/120 s, 5
  /// sweeps, settled on another face, 36 cm from its converged run;
  /// tall_box_tipping's tip further from its truth), for no accuracy gained
  /// anywhere in the sweep (docs/dynamics.md).
  [[nodiscard]] bool UsesJointBlock(const PairRows& pair) const {
    return m_jointBlock && pair.block >= 0 && pair.hasFriction && pair.pointCount >= 3;
  }
  /// FrictionSolve::CoupledBlock's patterns and solve operator of a pair with
  /// a normal block and friction, from its rows and warm-started impulses
  /// (built at the pair's first try of the step, before they change).
  [[nodiscard]] JointBlockRows BuildJointBlock(const PairRows& pair) const;
  /// FrictionSolve::CoupledBlock on a pair with a normal block and friction:
  /// true when accepted (normals and friction written and applied). Builds
  /// the operator at the step's first try.
  template <bool kTrack>
  bool SolveJointBlock(const PairRows& pair);
  enum JointState : unsigned char;
  /// One try of the block with the operator `joint`; records the outcome in `state`.
  template <bool kTrack>
  bool TryJointBlock(const PairRows& pair, const JointBlockRows& joint, JointState& state);
  template <bool kTrack>
  void Sweep();
  /// `sweeps` coloured sweeps as one chain of phases through m_runner (each
  /// sweep: each colour's normal rows, the overflow pairs'; then the
  /// friction rows likewise). Returns the largest tracked change (max is
  /// exact in any order, so the cut does not matter).
  double SweepsWide(int sweeps, bool track);
  void WarmStartPair(const PairRows& pair);
  /// Shock propagation's levels of this step's solver bodies and its pair order.
  void AssignShockLevels();
  void KeepLoadedPairs();
  [[nodiscard]] int PairLevel(const PairRows& pair) const;
  double ShockSweep(std::size_t begin, std::size_t end);
  bool HeldBlock(std::size_t order, const PairRows& pair, const ShockSides& sides, PairVelocities& v,
                 double& largest);

  SolverBodies m_bodies;
  std::vector<PairRows> m_pairs;
  std::vector<NormalRow> m_normals;      ///< one per point
  std::vector<FrictionRow> m_frictions;  ///< two per point (t1, t2) of the pairs with friction
  std::vector<PointCold> m_cold;         ///< one per point
  std::vector<Eigen::Matrix4d> m_blockInverses;
  /// Per block, FrictionSolve::CoupledBlock only: the operator, stored at the
  /// first try of the step unless that try refused the block.
  std::vector<JointBlockRows> m_jointBlocks;
  /// Per block, FrictionSolve::CoupledBlock's last outcome this step. Unbuilt:
  /// not tried yet this step (the operator is built at the first try; an
  /// operator that is not usable counts as refused). Refused
  /// (the pair slides or lifts): later sweeps of the step do not try again,
  /// a sliding pair stays sliding within a step. Accepted in this sweep's
  /// normal pass: the pair's friction rows are skipped in its friction
  /// pass, because the three patterns span every friction impulse that
  /// moves the bodies when the points are coplanar (a net force in the
  /// plane and a torque about n), so the rows could only redistribute
  /// impulse among the points.
  enum JointState : unsigned char { kJointUnbuilt, kJointUntried, kJointRefused, kJointAccepted };
  std::vector<JointState> m_jointState;
  WideContactSolver m_wide;
  bool m_useWide = false;     ///< ByColour selected at the last Prepare
  bool m_split = false;       ///< SplitImpulses selected at the last Prepare
  bool m_jointBlock = false;  ///< FrictionSolve::CoupledBlock selected at the last Prepare
  bool m_shock = false;       ///< MethodSettings::shockPropagation at the last Prepare
  // Shock propagation's scratch (kept between steps: no allocation in steady state).
  std::vector<unsigned char> m_shockTouching;  ///< per pair: some point within one slop of touching
  std::vector<int> m_shockLevels;              ///< per solver body
  std::vector<int> m_shockAdjStart;            ///< CSR offsets of the bodies' neighbours
  std::vector<int> m_shockAdj;
  std::vector<int> m_shockFill;
  std::vector<int> m_shockQueue;
  std::vector<int> m_shockOrder;  ///< pair indices with a level, by level
  std::vector<Vec3> m_shockPush;  ///< per solver body: the velocity gravity and forces gave it this step, m/s
  std::vector<Vec3> m_shockStart;            ///< per solver body: its velocity at the step's start, m/s
  std::vector<Vec3> m_shockWarmed;           ///< per solver body: its velocity after the warm start, m/s
  std::vector<unsigned char> m_shockLoaded;  ///< per solver body: carries a load heavier than a support
  std::vector<unsigned char> m_shockKeep;
  /// Per kept pair with a normal block: the block's pseudo-inverse with the
  /// held body's terms left out (built at the pass's first sweep of it).
  std::vector<Eigen::Matrix4d> m_shockBlocks;
  std::vector<unsigned char> m_shockBlockBuilt;  ///< per entry of m_shockOrder: the pass visits it
  int m_shockSweeps = 0;                         ///< sweeps of the last SolveVelocities' shock pass
  JointBlockCounts m_jointCounts;
  PhaseRunner m_runner;
  std::vector<JobPhase> m_phases;  ///< scratch: the chain of the coloured passes
  int m_newPairs = 0;              ///< pairs that did not persist
  int m_timedBounces = 0;          ///< points with a timed bounce (PointCold::timedBounce)
  double m_largestChange = 0.0;    ///< m/s, the largest row velocity change of this sweep
};

}  // namespace talus
