// World::Step: THE step. It walks the stage table (kStages,
// talus/step_stage.h: the stages, their order, what each does and whether
// it runs on worker threads) and runs each stage's function, timing it
// under its Stage in StepStatistics::seconds (StageTimes). The table's
// order is the pipeline of section 3 of the original write-up; the broad
// phase comes first because it is the only stage that may refuse.
//
// With MethodSettings::stepSolver = SoftStep the stages after the broad
// phase are the soft step's instead (RunSoftStage, SoftStepSolver):
// contacts, soft rows, the sub-steps (each integrating velocities and
// positions) under SolveVelocities, impulses stored, sleep; the soft step
// has no stage of its own for the integration or split impulses, which do
// nothing there.
//
// Nothing in here decides physics;
// the stages live in engine/src/dynamics and engine/src/collision.
//
// With WorldSettings::threads > 1 the stages the table marks
// `workerThreads` split their work across the world's JobPool; the others
// run on the calling thread. The results are bit-identical for any thread
// count (docs/threading.md).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <span>
#include <string>

#include "dynamics/integrator.h"
#include "talus/step_stage.h"
#include "talus/world.h"
#include "world/world_collide.h"
#include "world/world_data.h"
#include "world/world_validate.h"

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
  if (d.settings.methods.warmStarting)
    stats.warmStartedPoints = CarryImpulses(d.previousContacts, d.contacts);
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
  if (s.methods.warmStarting) d.solver.WarmStart();
  stats.velocitySweeps = d.solver.SolveVelocities(s.velocityIterations, s.methods.maxVelocityIterations,
                                                  s.methods.velocityTolerance);
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
    IntegratePositions(bodies, h, split, d.settings.methods.rotation, d.settings.methods.translation);
  });
}

void UpdateSleep(WorldData& d, double h, StepStatistics& stats) {
  if (!d.settings.sleeping) return;
  stats.islands = d.sleepManager.Update(d.sims, d.sleep, d.contacts, d.settings, h);
}

void SoftPrepareContacts(WorldData& d, double dt, StepStatistics& stats) {
  if (d.settings.methods.warmStarting)
    stats.warmStartedPoints = CarryImpulses(d.previousContacts, d.contacts);
  if (d.jobs->ThreadCount() > 1) {
    d.softSolver.SetPhaseRunner(
        [&d](std::span<const JobPhase> phases, const std::function<void(int, int, int)>& fn) {
          d.jobs->RunPhases(phases, fn);
        });
  } else {
    d.softSolver.SetPhaseRunner(nullptr);
  }
  d.softSolver.Prepare(d.sims, d.contacts, d.settings, dt, stats);
}

// The soft step (StepSolver::SoftStep, dynamics/soft_step_solver.h): the
// narrow phase once at the step's start, then the sub-steps (each
// integrating velocities, solving, integrating positions, relaxing) as one
// chain of phases on the world's threads, timed as SolveVelocities.
// Stages it has no work for do nothing.
void RunSoftStage(Stage stage, WorldData& d, double dt, StepStatistics& stats) {
  switch (stage) {
    case Stage::FindContacts:
      FindContacts(d, dt, stats);
      return;
    case Stage::PrepareContacts:
      SoftPrepareContacts(d, dt, stats);
      return;
    case Stage::SolveVelocities:
      stats.awakeBodies = d.softSolver.Step(d.sims, d.settings, dt);
      return;
    case Stage::ScatterAndStoreImpulses:
      d.softSolver.StoreImpulses(d.contacts);
      return;
    case Stage::UpdateSleep:
      UpdateSleep(d, dt, stats);
      return;
    case Stage::UpdateBroadPhase:  // run by Step itself: it may refuse
    case Stage::IntegrateVelocities:
    case Stage::SolveSplitImpulses:
    case Stage::IntegratePositions:
      return;
  }
}

// One stage of the sequential-impulse step.
void RunStage(Stage stage, WorldData& d, double dt, StepStatistics& stats) {
  switch (stage) {
    case Stage::IntegrateVelocities:
      stats.awakeBodies = IntegrateVelocitiesOnThreads(d, dt);
      return;
    case Stage::FindContacts:
      FindContacts(d, dt, stats);
      return;
    case Stage::PrepareContacts:
      PrepareContacts(d, dt, stats);
      return;
    case Stage::SolveVelocities:
      SolveVelocities(d, stats);
      return;
    case Stage::SolveSplitImpulses:
      SolveSplitImpulses(d, stats);
      return;
    case Stage::ScatterAndStoreImpulses:
      ScatterAndStoreImpulses(d);
      return;
    case Stage::IntegratePositions:
      IntegratePositionsOnThreads(d, dt);
      return;
    case Stage::UpdateSleep:
      UpdateSleep(d, dt, stats);
      return;
    case Stage::UpdateBroadPhase:  // run by Step itself: it may refuse
      return;
  }
}

}  // namespace

Result<StepStatistics> World::Step(double dt) {
  if (!std::isfinite(dt) || dt <= 0.0) {
    return Error{"World::Step: dt = " + std::to_string(dt) + " s must be finite and > 0"};
  }
  WorldData& d = *m_data;
  StepStatistics stats;
  StageClock clock(d.settings.timeStages);
  static_assert(kStages.front().stage == Stage::UpdateBroadPhase,
                "the only stage that may refuse runs first");
  if (const Result<int> proxies = UpdateBroadPhase(d, dt); !proxies) {
    return Error{"World::Step refused: " + proxies.GetError().message};
  }
  CountBodies(d, stats);
  stats.seconds[Stage::UpdateBroadPhase] = clock.Lap();

  const bool soft = d.settings.methods.stepSolver == StepSolver::SoftStep;
  for (const StageInfo& stage : std::span(kStages).subspan(1)) {
    if (soft) {
      RunSoftStage(stage.stage, d, dt, stats);
    } else {
      RunStage(stage.stage, d, dt, stats);
    }
    stats.seconds[stage.stage] = clock.Lap();
  }

  for (const double seconds : stats.seconds.byStage) stats.seconds.total += seconds;
#if defined(TALUS_VALIDATE)
  // The validation pass (world/world_validate.h), outside the timed stages.
  AbortIfInvalid(CheckStep(d, stats));
#endif
  return stats;
}

}  // namespace talus
