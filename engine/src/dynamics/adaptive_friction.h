// FrictionSolve::Adaptive: which friction rows each pair gets this step, the
// manifold's three rows (dynamics/manifold_friction.h) or the coupled block
// with its per-point rows (dynamics/coupled_block_solver.h), decided from
// the loads the pairs carried at the end of the last step (docs/dynamics.md,
// "Adaptive friction", has the measurements).
//
// The manifold rows are the cheaper solve, and with the slip at the centre
// of pressure they hold what the coupled block holds, with one exception:
// a light body under a heavy load. The load is counted in steps of the
// lighter moving body's own weight, m g h. Through a body that carries many
// times its weight, each sweep's friction impulses are small against the
// load, the error they leave is multiplied by it, and the sweeps a step has
// do not work it off. Measured on the testbed's heavy box on a pyramid of
// 1 kg boxes at 10 sweeps (talus-testbed sweep over the mass ratio): the
// manifold rows held 50:1 and threw 150:1 and everything above; the coupled
// block's exact stick solve held up to 5000:1. At 20 sweeps the manifold
// rows held every ratio up to 5000:1.
//
// A pair is loaded when its stored normal impulse, or the weight of its
// heavier moving body (which may rest on the lighter one before any impulse
// is stored), exceeds kAdaptiveLoadRatio of its lighter body's weights.
// ContactRowSet then gives the coupled block to every pair of the group of
// touching moving bodies the loaded pair belongs to: the load passes through
// all of them to the ground, and a group solved half one way and half the
// other was measured to fail where either way alone held
// (ContactRowSet::MarkBodiesUnderLoad).
//
// Stacks of equal bodies stay on the manifold rows: the most loaded pair of
// the 1240-box pyramid carries 17 of its boxes' weights, of the 2870-box
// pyramid 24.
//
// Every input is the pairs' own records, read in the serial pass of
// ContactRowSet::Prepare, so the choice is the same for any thread count.

#pragma once

#include <algorithm>

#include "dynamics/contact.h"

namespace talus {

/// Load, in weights of the lighter moving body per step, above which a
/// pair takes the coupled block: a third of the smallest load the manifold
/// rows were measured to drop at the default 10 sweeps (150:1, see above),
/// so that a load path has a factor 3 of margin.
inline constexpr double kAdaptiveLoadRatio = 50.0;

/// Whether a pair is loaded for FrictionSolve::Adaptive (its group then
/// takes the coupled block): whether its stored normal impulse, or the
/// weight impulse of its heavier moving body, exceeds kAdaptiveLoadRatio
/// times the lighter moving body's weight impulse m g h. `invMassA`, `invMassB` are
/// the pair's solver inverse masses (zero for a body contacts cannot move,
/// at least one nonzero), `gravity` is |WorldSettings::gravity| (m/s^2;
/// zero gives no weight to count in, and the manifold rows) and `h` the
/// step (s).
inline bool AdaptiveNeedsCoupledBlock(const Contact& contact, double invMassA, double invMassB,
                                      double gravity, double h) {
  double load = 0.0;
  for (int i = 0; i < contact.manifold.pointCount; ++i)
    load += contact.normalImpulse[static_cast<std::size_t>(i)];
  // The lighter moving body has the larger inverse mass; a heavier moving
  // body may rest its whole weight on it, stored or not yet.
  const double lighterWeight = gravity * h / std::max(invMassA, invMassB);
  const double heavierInvMass = std::min(invMassA, invMassB);
  if (heavierInvMass > 0.0) load = std::max(load, gravity * h / heavierInvMass);
  return gravity > 0.0 && load > kAdaptiveLoadRatio * lighterWeight;
}

}  // namespace talus
