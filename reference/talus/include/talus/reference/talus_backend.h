// The Talus engine behind the harness's Backend interface, in three
// variants that separate the write-up's choices from the improvements:
//
//   "talus"          the engine's defaults: Gauss-map-pruned SAT with the
//                    SAT cache, clipped manifolds reduced to 4 points, warm
//                    starting, Baumgarte stabilisation.
//   "talus-writeup"  the seed write-up's choices: full SAT (every face and
//                    edge pair), the write-up's manifolds, no SAT cache, no
//                    warm starting, Baumgarte stabilisation.
//   "talus-split"    the defaults plus split impulses (position correction
//                    that adds no kinetic energy).
//   "talus-coloured" the defaults with the coloured wide solver
//                    (ContactSolverKind::ColouredWide: pairs coloured, four
//                    per SIMD bundle) instead of the scalar pair order.
//
// Common to all: double precision; one World::Step(h) per Step(); mass,
// centre of mass and inertia from talus::reference::ComputeBodyMass (the
// same numbers the peers get), so the body frame is the scenario's frame
// and the centre of mass sits at its centroid, with no re-centring;
// sleeping off (the peers never sleep, and a sleeping body would hide
// jitter); the gyroscopic term as the scenario says (on:
// WorldSettings::rotation = MomentumSplittingFourthOrder, which keeps L
// with an O(h^4) energy error, MomentumSplitting (second order) for
// talus-writeup; off: ConstantRate); new contacts converged to 1e-9 m/s
// (WorldSettings::velocityTolerance; the engine's 1e-3 for talus-writeup,
// which has no extra sweeps anyway); position update exact for constant acceleration
// (WorldSettings::translation = ExactConstantAcceleration; symplectic Euler
// for talus-writeup); bounces timed as the scenario's world.bounceTiming
// says (auto: inside the step, the engine's default; at the step's
// boundary for talus-writeup); combine
// rules from the scenario (restitution "sqrt" has no engine rule and is
// refused); iterations from the run (0 = the engine's default, 10); threads
// from TalusBackendOptions (default 1).
#pragma once

#include "talus/harness/backend/backend.h"

namespace talus::reference {

/// How the testbed runs the Talus backends, beyond what a scenario says.
struct TalusBackendOptions {
  /// WorldSettings::threads of every world, [1, kMaxThreads]. Default 1, the
  /// engine's default. The results are bit-identical for any count, so this
  /// changes only the wall time (and the "threads" setting recorded).
  int threads = 1;
};

/// Registers "talus", "talus-writeup", "talus-split" and
/// "talus-coloured". A thread count
/// outside [1, kMaxThreads] is refused by every backend's Create, naming it.
void RegisterTalusBackends(harness::BackendRegistry& registry, TalusBackendOptions options = {});

}  // namespace talus::reference
