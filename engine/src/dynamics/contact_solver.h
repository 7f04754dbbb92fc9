// ContactSolver: Sequential Impulses (projected Gauss-Seidel) on contact
// and friction constraints, section 3 of the write-up after Catto (GDC
// 2005-2009), as the steps the world calls. It orchestrates parts with one
// job each (as Box2D v3 and Jolt split their solvers), each with its
// derivation beside it:
//   * ContactRowSet (dynamics/contact_row_set.h): the rows and solver
//     bodies of the step and their building (non-penetration, restitution
//     and friction rows, normal block pseudo-inverses; the data layout);
//   * SequentialImpulseSweeps (dynamics/sequential_impulse_sweeps.h): the
//     scalar Gauss-Seidel sweeps and warm start;
//   * CoupledBlockSolver (dynamics/coupled_block_solver.h): FrictionSolve::
//     CoupledBlock (and Adaptive's loaded groups), a face pair's normals
//     and friction as one block;
//   * ColouredContactDispatch (dynamics/coloured_contact_dispatch.h):
//     ContactOrder::ByColour's packed bundles and threads;
//   * ShockPropagation (dynamics/shock_propagation.h);
//   * SolveSplitImpulses (dynamics/split_impulses.h): the pseudo-velocity
//     rows of split impulses and timed bounces.
//
// Order. Each iteration sweeps all normal rows, then all friction rows.
//
// Extra sweeps. In a step with new pairs (no impulses to warm start from)
//   the sweeps go on past the minimum until the new pairs' rows change by
//   less than a tolerance, up to a maximum.
//
// After the sweeps Scatter() writes the solver bodies' velocities back.
#pragma once

#include <span>

#include "dynamics/body_sim.h"
#include "dynamics/coloured_contact_dispatch.h"
#include "dynamics/contact.h"
#include "dynamics/contact_row_set.h"
#include "dynamics/coupled_block_solver.h"
#include "dynamics/sequential_impulse_sweeps.h"
#include "dynamics/shock_propagation.h"
#include "dynamics/wide_contact_solver.h"
#include "jobs/job_pool.h"
#include "talus/step_statistics.h"
#include "talus/world_settings.h"

namespace talus {

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
  /// shock_propagation.cpp): the pairs level by level from the
  /// immovable bodies up, each pair's lower body held, up to `maxSweeps`
  /// sweeps per level until a sweep changes no velocity by more than
  /// `tolerance` (m/s). Returns the sweeps run. SolveVelocities runs it last
  /// when the setting is on.
  int PropagateShock(int maxSweeps, double tolerance) {
    return m_shock.Propagate(m_rows, maxSweeps, tolerance);
  }
  /// Runs `iterations` sweeps of the split-impulse pseudo-velocity rows
  /// (and of the timed bounces' position rows).
  void SolveSplitImpulses(int iterations);
  /// Shock propagation's sweeps in the last SolveVelocities (0 when off).
  [[nodiscard]] int ShockSweeps() const { return m_shockSweeps; }
  /// Points of the last Prepare that bounce inside the step.
  [[nodiscard]] int TimedBounceCount() const { return m_rows.TimedBounceCount(); }
  /// Whether this step's positions take pseudo velocities: split impulses
  /// were selected at the last Prepare, or some point bounces inside the
  /// step (its position row needs them whatever the position correction).
  /// Then SolveSplitImpulses runs, Scatter writes them and the position
  /// update adds them.
  [[nodiscard]] bool UsesPseudoVelocities() const { return m_split || m_rows.TimedBounceCount() > 0; }
  /// Writes the solved velocities of the bodies contacts can move back to
  /// `bodies` (the array handed to Prepare), with `pseudo` the split-impulse
  /// pseudo velocities too. Bodies without rows are not touched.
  void Scatter(std::span<BodySim> bodies, bool pseudo) const { m_rows.Bodies().Scatter(bodies, pseudo); }
  /// Writes the accumulated impulses back for next step's warm start.
  void StoreImpulses(std::span<Contact> contacts) const { m_rows.StoreImpulses(contacts); }

  /// Number of point rows built by the last Prepare.
  [[nodiscard]] int PointCount() const { return static_cast<int>(m_rows.Normals().size()); }
  /// The coloured solver of the last Prepare (empty unless ByColour).
  [[nodiscard]] const WideContactSolver& Wide() const { return m_coloured.Wide(); }

  /// The coupled block's tries in the last step's sweeps (CoupledBlock, or
  /// Adaptive's loaded groups).
  using CoupledBlockCounts = CoupledBlockSolver::Counts;
  [[nodiscard]] const CoupledBlockCounts& LastCoupledBlockCounts() const { return m_coupled.LastCounts(); }

 private:
  /// One sweep over every row (coloured or scalar); with `track`, returns
  /// the largest velocity change of a row of a new pair (m/s).
  double SweepOnce(bool track);

  ContactRowSet m_rows;
  SequentialImpulseSweeps m_sweeps;
  CoupledBlockSolver m_coupled;
  ColouredContactDispatch m_coloured;
  ShockPropagation m_shock;
  PhaseRunner m_runner;
  bool m_useWide = false;  ///< ByColour selected at the last Prepare
  bool m_split = false;    ///< SplitImpulses selected at the last Prepare
  bool m_shockOn = false;  ///< MethodSettings::shockPropagation at the last Prepare
  int m_shockSweeps = 0;   ///< sweeps of the last SolveVelocities' shock pass
};

}  // namespace talus
