// World::Step: THE step. It reads top to bottom as the pipeline of section 3
// of the original write-up, each stage a function of its own and timed under
// its own name in StepStatistics::seconds (StageTimes):
//
//   0. UpdateBroadPhase         bounding spheres in (the only stage that may
//                               refuse, so it runs before anything changes)
//   1. IntegrateVelocities      gravity, forces, torques
//   2. FindContacts             sorted pairs; per pair kept, rebuilt (manifold
//                               reuse) or collided (SAT, manifold, persistent
//                               points); one persistent contact per touching pair
//   3. PrepareContacts          warm-start matching, constraint rows (colours)
//   4. SolveVelocities          warm start, sequential-impulse sweeps
//   5. SolveSplitImpulses       split-impulse pseudo-velocities (when selected),
//                               timed bounces' position rows
//   6. ScatterAndStoreImpulses  solved velocities back to the bodies, each
//                               row's impulse into its contact (next warm start)
//   7. IntegratePositions       x += h v, q = exp(h w / 2) q (or the schemes of
//                               WorldSettings::rotation and ::translation)
//   8. UpdateSleep              islands at rest fall asleep
//
// With WorldSettings::stepSolver = SoftStep the stages after the broad
// phase are StepSoft's instead: contacts, soft rows, the sub-steps (each
// integrating velocities and positions), impulses stored, sleep.
//
// Nothing in here decides physics;
// the stages live in engine/src/dynamics and engine/src/collision.
//
// With WorldSettings::threads > 1 the integration runs per body, and the
// proxies and the narrow phase (world_collide.cpp) per pair, on the world's
// JobPool; every other stage runs on the calling thread. The results are
// bit-identical for any thread count (docs/threading.md).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <span>
#include <string>

#include "dynamics/integrator.h"
#include "talus/world.h"
#include "world/world_collide.h"
#include "world/world_data.h"

namespace talus {
namespace {

// Wall-clock seconds since construction or the last Lap(); 0 without
// reading the clock when the world does not time its stages.
class StageClock {
 public:
  explicit StageClock(bool on) : m_on(on) {
    if (m_on) m_last = std::chrono::steady_clock::now();
  }
  double Lap() {
    if (!m_on) return 0.0;
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - m_last).count();
    m_last = now;
    return seconds;
  }

 private:
  bool m_on;
  std::chrono::steady_clock::time_point m_last;
};

void CountBodies(const WorldData& d, StepStatistics& stats) {
  stats.bodies = d.liveBodies;
  for (const BodySim& sim : d.sims) {
    if (sim.type == BodyType::Dynamic && !sim.awake) ++stats.sleepingBodies;
  }
}

// Warm starting pairs this step's contacts with last step's by feature id;
// then the solver's rows are built from the contacts.
// The coloured solver hands each colour's bundles to the world's pool; the
// scalar solver ignores the runner. With one thread no runner is set, so a
// colour runs as one range on the caller (the results are the same bits
// either way: tests/threads, tests/dynamics/coloured_solver_test.cpp).
void PrepareContacts(WorldData& d, double h, StepStatistics& stats) {
  if (d.settings.warmStarting) stats.warmStartedPoints = CarryImpulses(d.previousContacts, d.contacts);
  if (d.jobs->ThreadCount() > 1) {
    d.solver.SetPhaseRunner(
        [&d](std::span<const JobPhase> phases, const std::function<void(int, int, int)>& fn) {
          d.jobs->RunPhases(phases, fn);
        });
  } else {
    d.solver.SetPhaseRunner(nullptr);
  }
  d.solver.Prepare(d.sims, d.contacts, d.settings, h, stats);
}

void SolveVelocities(WorldData& d, StepStatistics& stats) {
  const WorldSettings& s = d.settings;
  if (s.warmStarting) d.solver.WarmStart();
  stats.velocitySweeps =
      d.solver.SolveVelocities(s.velocityIterations, s.maxVelocityIterations, s.velocityTolerance);
  stats.shockSweeps = d.solver.ShockSweeps();
}

// Split impulses: pseudo-velocities that push overlapping pairs apart
// without adding kinetic energy (when that correction is selected), and put
// timed bounces on their reflected flights.
void SolveSplitImpulses(WorldData& d, StepStatistics& stats) {
  if (!d.solver.UsesPseudoVelocities()) return;
  d.solver.SolveSplitImpulses(d.settings.positionIterations);
  stats.positionSweeps = d.settings.positionIterations;
}

// The solver works on its own gathered copy of the velocities; they go back
// to the bodies here, before the position update reads them, and each row's
// accumulated impulse goes into its contact for the next step's warm start.
void ScatterAndStoreImpulses(WorldData& d) {
  d.solver.Scatter(d.sims, d.solver.UsesPseudoVelocities());
  d.solver.StoreImpulses(d.contacts);
}

// Bodies per ParallelFor chunk of the integration: a body's update is
// 50-300 ns, so a chunk is tens of microseconds, far above the cost of
// claiming it. The boundaries depend on the body count only, never on the
// thread count, and each body is updated by exactly one thread.
constexpr int kBodyGrain = 128;

// The velocity half of the integrator over every body, on the world's
// threads; returns the bodies integrated (an integer sum, the same in any
// order).
int IntegrateVelocitiesOnThreads(WorldData& d, double h) {
  std::atomic<int> integrated{0};
  d.jobs->ParallelFor(static_cast<int>(d.sims.size()), kBodyGrain, [&d, &integrated, h](int begin, int end) {
    const std::span<BodySim> bodies(d.sims.data() + begin, static_cast<std::size_t>(end - begin));
    integrated.fetch_add(IntegrateVelocities(bodies, d.settings.gravity, h));
  });
  return integrated.load();
}

// The position half of the integrator over every body, on the world's threads.
void IntegratePositionsOnThreads(WorldData& d, double h) {
  const bool split = d.solver.UsesPseudoVelocities();
  d.jobs->ParallelFor(static_cast<int>(d.sims.size()), kBodyGrain, [&d, h, split](int begin, int end) {
    const std::span<BodySim> bodies(d.sims.data() + begin, static_cast<std::size_t>(end - begin));
    IntegratePositions(bodies, h, split, d.settings.rotation, d.settings.translation);
  });
}

void UpdateSleep(WorldData& d, double h, StepStatistics& stats) {
  if (!d.settings.sleeping) return;
  stats.islands = d.sleepManager.Update(d.sims, d.sleep, d.contacts, d.settings, h);
}

// The soft step (StepSolver::SoftStep, dynamics/soft_step_solver.h): the
// narrow phase once at the step's start, then the sub-steps (each
// integrating velocities, solving, integrating positions, relaxing) as one
// chain of phases on the world's threads. Timed under the same stage names:
// the sub-step chain, integration included, is solveVelocities.
void StepSoft(WorldData& d, double dt, StepStatistics& stats, StageClock& clock) {
  FindContacts(d, dt, stats);
  stats.seconds.findContacts = clock.Lap();

  if (d.settings.warmStarting) stats.warmStartedPoints = CarryImpulses(d.previousContacts, d.contacts);
  if (d.jobs->ThreadCount() > 1) {
    d.softSolver.SetPhaseRunner(
        [&d](std::span<const JobPhase> phases, const std::function<void(int, int, int)>& fn) {
          d.jobs->RunPhases(phases, fn);
        });
  } else {
    d.softSolver.SetPhaseRunner(nullptr);
  }
  d.softSolver.Prepare(d.sims, d.contacts, d.settings, dt, stats);
  stats.seconds.prepareContacts = clock.Lap();

  stats.awakeBodies = d.softSolver.Step(d.sims, d.settings, dt);
  stats.seconds.solveVelocities = clock.Lap();

  d.softSolver.StoreImpulses(d.contacts);
  stats.seconds.scatterAndStoreImpulses = clock.Lap();
}

}  // namespace

Result<StepStatistics> World::Step(double dt) {
  if (!std::isfinite(dt) || dt <= 0.0) {
    return Error{"World::Step: dt = " + std::to_string(dt) + " s must be finite and > 0"};
  }
  WorldData& d = *m_data;
  StepStatistics stats;
  StageClock clock(d.settings.timeStages);
  if (const Result<int> proxies = UpdateBroadPhase(d, dt); !proxies) {
    return Error{"World::Step refused: " + proxies.GetError().message};
  }
  CountBodies(d, stats);
  stats.seconds.updateBroadPhase = clock.Lap();

  if (d.settings.stepSolver == StepSolver::SoftStep) {
    StepSoft(d, dt, stats, clock);
    UpdateSleep(d, dt, stats);
    stats.seconds.sleep = clock.Lap();
    const StageTimes& t = stats.seconds;
    stats.seconds.total = t.updateBroadPhase + t.findContacts + t.prepareContacts + t.solveVelocities +
                          t.scatterAndStoreImpulses + t.sleep;
    return stats;
  }

  stats.awakeBodies = IntegrateVelocitiesOnThreads(d, dt);
  stats.seconds.integrateVelocities = clock.Lap();

  FindContacts(d, dt, stats);
  stats.seconds.findContacts = clock.Lap();

  PrepareContacts(d, dt, stats);
  stats.seconds.prepareContacts = clock.Lap();

  SolveVelocities(d, stats);
  stats.seconds.solveVelocities = clock.Lap();

  SolveSplitImpulses(d, stats);
  stats.seconds.solveSplitImpulses = clock.Lap();

  ScatterAndStoreImpulses(d);
  stats.seconds.scatterAndStoreImpulses = clock.Lap();

  IntegratePositionsOnThreads(d, dt);
  stats.seconds.integratePositions = clock.Lap();

  UpdateSleep(d, dt, stats);
  stats.seconds.sleep = clock.Lap();

  const StageTimes& t = stats.seconds;
  stats.seconds.total = t.updateBroadPhase + t.integrateVelocities + t.findContacts + t.prepareContacts +
                        t.solveVelocities + t.solveSplitImpulses + t.scatterAndStoreImpulses +
                        t.integratePositions + t.sleep;
  return stats;
}

}  // namespace talus
