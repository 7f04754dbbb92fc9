// The Talus engine behind the harness's Backend interface, in rows that
// separate the engine's defaults from the write-up's choices and from the
// other options:
//
//   "talus"          WorldSettings{} unchanged but for what the scenario
//                    states (below): the configuration a user of the
//                    library gets, and the one the testbed validates.
//   "talus-writeup"  the seed write-up's choices (docs/write-up.md) in place
//                    of every improvement: full SAT, its manifolds, no SAT
//                    cache, reuse or persistent points, a fixed speculative
//                    margin, no warm starting, row-by-row normals and
//                    per-point friction at a fixed sweep count, symplectic
//                    Euler, bounces at the step's boundary, the
//                    second-order rotation step when the scenario asks for
//                    the gyroscopic term.
//   "talus-split"    the defaults with split impulses (position correction
//                    that adds no kinetic energy).
//   "talus-coloured" the defaults with the coloured wide solver
//                    (ContactOrder::ByColour: pairs coloured, four
//                    per SIMD bundle) and the per-point friction it has.
//   "talus-soft"     the defaults with the soft step (MethodSettings::
//                    stepSolver = SoftStep: sub-stepped soft contacts).
//   "talus-manifold" the defaults with friction per manifold on every
//                    pair (FrictionSolve::PerManifold: slip at the centre
//                    of pressure and a spin row, no coupled block).
//   "talus-coupled"  the defaults with the coupled block on every face
//                    (FrictionSolve::CoupledBlock, the default before
//                    Adaptive).
//
// Every departure is a method switch (WorldSettings::methods).
//
// What a scenario states, common to all: gravity; iterations from the run
// (0 = the engine's default, 10); the combine rules (restitution "sqrt" has
// no engine rule and is refused); sleeping off (the peers never sleep, and
// a sleeping body would hide jitter); the gyroscopic term (off:
// MethodSettings::rotation = ConstantRate); world.broadPhase (auto keeps the
// engine's); world.bounceTiming (auto keeps the row's). Threads come from
// TalusBackendOptions (default 1). Each row's departures from the engine's
// default are listed in its settings (engineDefault and effect) and in
// docs/testbed-backends.md, "The Talus rows". Mass, centre of mass and
// inertia come from talus::reference::ComputeBodyMass (the same numbers the
// peers get), so the body frame is the scenario's frame and the centre of
// mass sits at its centroid, with no re-centring.
#pragma once

#include <string_view>

#include "talus/harness/backend/backend.h"
#include "talus/result.h"
#include "talus/world_settings.h"

namespace talus::reference {

/// How the testbed runs the Talus backends, beyond what a scenario says.
struct TalusBackendOptions {
  /// WorldSettings::threads of every world, [1, kMaxThreads]. Default 1, the
  /// engine's default. The results are bit-identical for any count, so this
  /// changes only the wall time (and the "threads" setting recorded).
  int threads = 1;
};

/// Registers "talus", "talus-writeup", "talus-split", "talus-coloured",
/// "talus-soft", "talus-manifold" and "talus-coupled". A thread count
/// outside [1, kMaxThreads] is refused by every backend's Create, naming it.
void RegisterTalusBackends(harness::BackendRegistry& registry, TalusBackendOptions options = {});

/// The WorldSettings the Talus row named `row` ("talus", "talus-writeup",
/// "talus-split", "talus-coloured", "talus-soft", "talus-manifold", "talus-coupled") runs `run` with, as
/// its backend hands
/// them to World::Create; an Error naming an unknown row, or a scenario the
/// engine cannot pose (a restitution combine rule it lacks).
Result<WorldSettings> TalusRowSettings(const harness::Run& run, std::string_view row,
                                       const TalusBackendOptions& options = {});

}  // namespace talus::reference
