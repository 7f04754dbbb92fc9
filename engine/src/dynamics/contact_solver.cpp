// ContactSolver: the steps of the contact solve, each handed to the part
// that does it (dynamics/contact_solver.h lists them).
#include "dynamics/contact_solver.h"

#include "dynamics/split_impulses.h"

namespace talus {

void ContactSolver::Prepare(std::span<const BodySim> bodies, std::span<const Contact> contacts,
                            const WorldSettings& settings, double h, StepStatistics& stats) {
  m_split = settings.methods.positionCorrection == PositionCorrection::SplitImpulses;
  m_shockOn = settings.methods.shockPropagation;
  m_useWide = settings.methods.contactOrder == ContactOrder::ByColour;
  m_rows.Prepare(bodies, contacts, settings, h, m_runner, stats);
  m_coupled.Reset(settings.methods.frictionSolve == FrictionSolve::CoupledBlock ||
                      settings.methods.frictionSolve == FrictionSolve::Adaptive,
                  m_rows.BlockCount());
  if (m_shockOn) m_shock.Prepare(bodies, contacts, m_rows, settings.slop);
  if (m_useWide) m_coloured.Build(m_rows, m_runner, stats);
}

// Warm start: each point's accumulated impulse lambda_n n + lambda_1 t1 +
// lambda_2 t2, applied through the rows' precomputed images. Coloured: the
// colours' bundles, then the overflow pairs.
void ContactSolver::WarmStart() {
  if (m_useWide) {
    m_coloured.WarmStart(m_rows, m_runner);
  } else {
    SequentialImpulseSweeps::WarmStart(m_rows);
  }
}

double ContactSolver::SweepOnce(bool track) {
  if (m_useWide) return m_coloured.Sweeps(m_rows, m_coupled, m_sweeps, 1, track, m_runner);
  return m_sweeps.Sweep(m_rows, m_coupled, track);
}

// Each iteration sweeps every normal row, then every friction row (the
// order Bullet uses). Measured on a 10-box column: interleaving friction
// after each point's normal row left ten times the residual rocking
// (0.1 rad/s against 0.01 rad/s at 10 iterations), because a corner's
// friction row then reads a normal impulse the other corners have not yet
// balanced. The friction bound still follows the normal impulse as it
// changes: every friction pass reads the current values.
//
// Past `minIterations`, when some pair is new this step, further sweeps
// over all rows go on while the last one still changed a row of a new pair
// by more than `tolerance` (m/s), up to `maxIterations` sweeps in all. A new
// pair has no accumulated impulse to start from: under a stack whose
// contacts are all new, the load must diffuse through the chain one contact
// per sweep, and ten sweeps leave a 10-box column sagging 1.5 cm. Measured
// alternatives: sweeping everything to convergence every step cost 6x the
// solver time on the 1240-cube pyramid (its warm-started rows never settle
// to 1e-3 m/s in ten sweeps); sweeping the new pairs' rows alone pushed
// bodies into the contacts left unsolved and the pyramid drifted 0.45 m.
//
// Coloured (ContactOrder::ByColour), the same sweeps visit each
// colour's pairs four at a time, then the overflow pairs one by one; the
// impulses go back to the scalar rows at the end, where the position
// passes and StoreImpulses read them.
int ContactSolver::SolveVelocities(int minIterations, int maxIterations, double tolerance) {
  // Shock propagation reads how far the warm start left each body from
  // where the step began (ShockPropagation::KeepLoadedPairs).
  if (m_shockOn) m_shock.NoteWarmed(m_rows.Bodies());
  int sweeps = 0;
  if (m_useWide && minIterations > 0) {
    // The untracked sweeps need no result between them: one chain.
    m_coloured.Sweeps(m_rows, m_coupled, m_sweeps, minIterations, false, m_runner);
    sweeps = minIterations;
  }
  for (; sweeps < minIterations; ++sweeps) SweepOnce(false);
  if (m_rows.NewPairCount() != 0) {
    for (; sweeps < maxIterations;) {
      ++sweeps;
      if (SweepOnce(true) <= tolerance) break;
    }
  }
  if (m_useWide) m_coloured.Unpack(m_rows, m_runner);
  m_shockSweeps = m_shockOn ? PropagateShock(minIterations, tolerance) : 0;
  return sweeps;
}

void ContactSolver::SolveSplitImpulses(int iterations) { talus::SolveSplitImpulses(m_rows, iterations); }

}  // namespace talus
