// ContactRowSet: the rows of one step's contacts and their building
// (Prepare), the data every other part of the contact solver reads
// (dynamics/contact_solver.h has the orchestration).
//
// Non-penetration. For one contact point p of the pair (A, B), normal n
// from B to A, rA = p - cA, rB = p - cB, relative velocity at p
//   dv = (vA + wA x rA) - (vB + wB x rB),
// C = depth along n must not grow: Cdot = n . dv >= target.
//   Jacobian  J = [ n, rA x n, -n, -rB x n ]
//   Effective mass  m_n = 1 / (1/mA + 1/mB + (rA x n) . IA^-1 (rA x n)
//                                           + (rB x n) . IB^-1 (rB x n))
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
// Friction rows. Cdot = t_k . dv = 0 for two tangents t1, t2 orthogonal to
//   n (t1 along the sliding velocity when there is one, so the sliding
//   direction gets the whole Coulomb bound).
//   Jacobian  J = [ t, rA x t, -t, -rB x t ],  m_t likewise with t for n.
//
// Normal block. A pair of 2-4 points gets K = J M^-1 J^T of its normal rows
//   (4x4, rank 3 for four points) and its pseudo-inverse
//   (dynamics/normal_block.h), for the block solve of the sweeps
//   (dynamics/sequential_impulse_sweeps.h).
//
// Data (the layout the sweeps walk; see docs/dynamics.md). Prepare()
//   gathers the velocities of every body a row touches into SolverBodies
//   (48 bytes each; bodies contacts cannot move keep zero inverse mass and
//   inertia there, so the sweep needs no branch and never writes them) and
//   builds, in dense vectors that keep their capacity between steps:
//   * one PairRows header per touching pair (solver-body indices, normal,
//     tangents, inverse masses, friction, flags);
//   * one NormalRow per point and two FrictionRows per point (one per
//     tangent; on manifold rows, PerManifold's pairs and Adaptive's
//     unloaded ones, three per pair instead, dynamics/manifold_friction.h
//     and adaptive_friction.h), each with its Jacobian's angular
//     parts r x d precomputed together with their images under the inverse inertia, IA^-1 (rA x d)
//     and IB^-1 (rB x d). A row is then
//       Cdot = d.(vA - vB) + (rA x d).wA - (rB x d).wB     (two dot products)
//       vA += mA^-1 dl d, wA += dl IA^-1 (rA x d), B the opposite (axpys),
//     no cross product and no matrix product inside the sweep;
//   * cold per-point data (split-impulse target and impulse, arms) and the
//     block pseudo-inverses apart.
//   The iterations never allocate. Pairs where neither body can move under
//   contact (static, kinematic, asleep) build no rows; mu == 0 builds no
//   friction rows, e == 0 no restitution work.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "dynamics/body_sim.h"
#include "dynamics/contact.h"
#include "dynamics/contact_rows.h"
#include "dynamics/normal_block.h"
#include "dynamics/solver_body.h"
#include "jobs/job_pool.h"
#include "talus/step_statistics.h"
#include "talus/world_settings.h"

namespace talus {

class ContactRowSet {
 public:
  /// Builds the rows of `contacts` for a step of `h` seconds and gathers
  /// the velocities of their bodies from `bodies`, loading the accumulated
  /// impulses (zero, or last step's when warm starting). The pairs' rows
  /// are built through `runner` (any cut, the same bits). Adds its counts
  /// to `stats`.
  void Prepare(std::span<const BodySim> bodies, std::span<const Contact> contacts,
               const WorldSettings& settings, double h, const PhaseRunner& runner, StepStatistics& stats);
  /// Writes the accumulated impulses back for next step's warm start.
  void StoreImpulses(std::span<Contact> contacts) const;

  SolverBodies& Bodies() { return m_bodies; }
  [[nodiscard]] const SolverBodies& Bodies() const { return m_bodies; }
  [[nodiscard]] std::span<const PairRows> Pairs() const { return m_pairs; }
  std::vector<NormalRow>& Normals() { return m_normals; }
  [[nodiscard]] const std::vector<NormalRow>& Normals() const { return m_normals; }
  std::vector<FrictionRow>& Frictions() { return m_frictions; }
  [[nodiscard]] const std::vector<FrictionRow>& Frictions() const { return m_frictions; }
  std::vector<PointCold>& Cold() { return m_cold; }
  [[nodiscard]] const std::vector<PointCold>& Cold() const { return m_cold; }
  /// Per point of a pair with manifold friction: its offset's length from
  /// the manifold's centre in the contact plane, metres (the spin row's
  /// lever, dynamics/manifold_friction.h); unset for other pairs.
  [[nodiscard]] const std::vector<double>& Levers() const { return m_levers; }
  [[nodiscard]] std::span<const Eigen::Matrix4d> BlockInverses() const { return m_blockInverses; }
  /// Normal blocks of the last Prepare (PairRows::block indexes them).
  [[nodiscard]] int BlockCount() const { return static_cast<int>(m_blockInverses.size()); }
  /// Pairs of the last Prepare that did not persist (no impulses to warm start from).
  [[nodiscard]] int NewPairCount() const { return m_newPairs; }
  /// Points of the last Prepare that bounce inside the step (PointCold::timedBounce).
  [[nodiscard]] int TimedBounceCount() const { return m_timedBounces; }

 private:
  /// Integer counts a pair's rows add to the step's statistics, summed per
  /// chunk of pairs (an integer sum: the same in any order).
  struct PrepareCounts {
    int timedBounces = 0;
    int restitutionSkipped = 0;
  };
  /// The places the serial pass gave the rows: totals over all pairs.
  struct RowTotals {
    int points = 0;
    int frictions = 0;
    int blocks = 0;
  };
  /// The serial pass: which contacts get rows, their solver bodies (in
  /// contact order, the numbering every step's bits follow) and each
  /// pair's header with its rows' places.
  RowTotals AddPairHeaders(std::span<const BodySim> bodies, std::span<const Contact> contacts,
                           const WorldSettings& settings, StepStatistics& stats);
  /// FrictionSolve::Adaptive: which bodies' pairs take the coupled block
  /// this step (m_underLoad): the groups of touching moving bodies with a
  /// heavily loaded pair.
  void MarkBodiesUnderLoad(std::span<const BodySim> bodies, std::span<const Contact> contacts,
                           const WorldSettings& settings, double h);
  /// The header of `contact` (index `c`) with its rows starting at `totals`.
  PairRows MakePairHeader(std::span<const BodySim> bodies, const Contact& contact, int c,
                          const WorldSettings& settings, RowTotals& totals);
  /// The parallel pass: each pair's rows in the places the serial pass gave them.
  void BuildPairsOnThreads(std::span<const BodySim> bodies, std::span<const Contact> contacts,
                           const WorldSettings& settings, double h, const PhaseRunner& runner,
                           StepStatistics& stats);
  /// The rows of one pair whose header the serial pass filled (its
  /// bodies, row offsets, block slot): writes only that pair's rows, so
  /// pairs may be prepared on any thread in any order.
  void PreparePair(std::span<const BodySim> bodies, const Contact& contact, const WorldSettings& settings,
                   double h, PairRows& pair, PrepareCounts& counts);
  /// Point `i`'s normal row, cold data and friction rows.
  void PreparePoint(const BodySim& a, const BodySim& b, const Contact& contact, int i,
                    const WorldSettings& settings, double h, const PairRows& pair, PrepareCounts& counts);
  /// The two friction rows of point `i` at arms rA, rB.
  void PrepareFrictionRows(const Contact& contact, int i, const Vec3& rA, const Vec3& rB,
                           const WorldSettings& settings, const PairRows& pair);
  /// The manifold friction rows of a pair (PairRows::manifoldFriction) and
  /// its points' levers.
  void PrepareManifoldFriction(const BodySim& a, const BodySim& b, const Contact& contact,
                               const WorldSettings& settings, const PairRows& pair);
  /// A manifold-friction pair's impulses back as per-point vectors.
  void StoreManifoldFriction(const PairRows& pair, Contact& contact) const;
  void PrepareBlock(const PairRows& pair);

  SolverBodies m_bodies;
  std::vector<PairRows> m_pairs;
  std::vector<NormalRow> m_normals;  ///< one per point
  /// Two per point (t1, t2) of the pairs with friction, or the manifold's
  /// rows (ManifoldFrictionRowCount) of a pair with manifold friction.
  std::vector<FrictionRow> m_frictions;
  /// One per point under FrictionSolve::PerManifold or Adaptive (empty
  /// otherwise); written for manifold-friction pairs only.
  std::vector<double> m_levers;
  std::vector<PointCold> m_cold;  ///< one per point
  /// Per body (world index), under Adaptive: 1 when its group carries a
  /// load that calls for the coupled block (MarkBodiesUnderLoad).
  std::vector<unsigned char> m_underLoad;
  /// MarkBodiesUnderLoad's union-find parents, per body (world index).
  std::vector<int> m_group;
  std::vector<Eigen::Matrix4d> m_blockInverses;
  int m_newPairs = 0;      ///< pairs that did not persist
  int m_timedBounces = 0;  ///< points with a timed bounce (PointCold::timedBounce)
};

}  // namespace talus
