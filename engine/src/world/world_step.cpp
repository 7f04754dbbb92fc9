// World::Step: THE step. After the broad phase (the only stage that may
// refuse, so it runs first) it walks its step solver's stage table,
// kSequentialImpulseStages or kSoftStepStages: each entry names a stage of
// kStages (talus/step_stage.h: the stages, their order, what each does and
// whether it runs on worker threads) and carries the function that does
// it. Each stage that ran is timed under its Stage in
// StepStatistics::seconds (StageTimes) and marked in StageTimes::ran; a
// stage its solver lacks (the soft step has no integration or split
// impulse stage of its own) has neither. The order is the pipeline of
// section 3 of the original write-up.
//
// Nothing in here decides physics;
// the stages live in engine/src/dynamics and engine/src/collision.
//
// With WorldSettings::threads > 1 the stages the table marks
// `workerThreads` split their work across the world's JobPool; the others
// run on the calling thread. The results are bit-identical for any thread
// count (docs/threading.md).
#include <algorithm>
#include <array>
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

// The solver's rows are built from the contacts (FindContacts has already
// carried last step's impulses into them: world/world_collide.h).
// The coloured solver hands each colour's bundles to the world's pool; the
// scalar solver ignores the runner. With one thread no runner is set, so a
// colour runs as one range on the caller (the results are the same bits
// either way: tests/threads, tests/dynamics/coloured_solver_test.cpp).
void PrepareContacts(WorldData& d, double h, StepStatistics& stats) {
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

// Each stage's function, one signature for all: the world, the step in
// seconds and the step's statistics.
using StageFunction = void (*)(WorldData&, double, StepStatistics&);

// One entry of a step solver's stage table: the stage (its name, order and
// threads in kStages) and the function that does its work.
struct StageStep {
  Stage stage;
  StageFunction run;
};

// The Sequential Impulses step (MethodSettings::stepSolver =
// SequentialImpulses): every stage of kStages after the broad phase.
constexpr std::array<StageStep, 8> kSequentialImpulseStages = {{
    {Stage::IntegrateVelocities,
     [](WorldData& d, double h, StepStatistics& stats) {
       stats.awakeBodies = IntegrateVelocitiesOnThreads(d, h);
     }},
    {Stage::FindContacts, [](WorldData& d, double h, StepStatistics& stats) { FindContacts(d, h, stats); }},
    {Stage::PrepareContacts,
     [](WorldData& d, double h, StepStatistics& stats) { PrepareContacts(d, h, stats); }},
    {Stage::SolveVelocities, [](WorldData& d, double, StepStatistics& stats) { SolveVelocities(d, stats); }},
    {Stage::SolveSplitImpulses,
     [](WorldData& d, double, StepStatistics& stats) { SolveSplitImpulses(d, stats); }},
    {Stage::ScatterAndStoreImpulses,
     [](WorldData& d, double, StepStatistics&) { ScatterAndStoreImpulses(d); }},
    {Stage::IntegratePositions,
     [](WorldData& d, double h, StepStatistics&) { IntegratePositionsOnThreads(d, h); }},
    {Stage::UpdateSleep, [](WorldData& d, double h, StepStatistics& stats) { UpdateSleep(d, h, stats); }},
}};

// The soft step (StepSolver::SoftStep, dynamics/soft_step_solver.h): the
// narrow phase once at the step's start, then the sub-steps (each
// integrating velocities, solving, integrating positions, relaxing) as one
// chain of phases on the world's threads, timed as SolveVelocities. It has
// no stage of its own for the integration or split impulses, so its table
// leaves them out and they report no time.
constexpr std::array<StageStep, 5> kSoftStepStages = {{
    {Stage::FindContacts, [](WorldData& d, double h, StepStatistics& stats) { FindContacts(d, h, stats); }},
    {Stage::PrepareContacts,
     [](WorldData& d, double h, StepStatistics& stats) { SoftPrepareContacts(d, h, stats); }},
    {Stage::SolveVelocities,
     [](WorldData& d, double h, StepStatistics& stats) {
       stats.awakeBodies = d.softSolver.Step(d.sims, d.settings, h);
     }},
    {Stage::ScatterAndStoreImpulses,
     [](WorldData& d, double, StepStatistics&) { d.softSolver.StoreImpulses(d.contacts); }},
    {Stage::UpdateSleep, [](WorldData& d, double h, StepStatistics& stats) { UpdateSleep(d, h, stats); }},
}};

// A solver's table runs its stages in kStages order, after the broad phase
// (which World::Step runs itself: it may refuse), each stage once.
template <std::size_t N>
constexpr bool InStepOrder(const std::array<StageStep, N>& table) {
  Stage last = Stage::UpdateBroadPhase;
  for (const StageStep& step : table) {
    if (!(static_cast<int>(step.stage) > static_cast<int>(last)) || step.run == nullptr) return false;
    last = step.stage;
  }
  return true;
}
static_assert(InStepOrder(kSequentialImpulseStages), "the Sequential Impulses stages run in kStages order");
static_assert(InStepOrder(kSoftStepStages), "the soft step's stages run in kStages order");

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

  stats.seconds.ran[static_cast<std::size_t>(Stage::UpdateBroadPhase)] = true;

  const std::span<const StageStep> stages = d.settings.methods.stepSolver == StepSolver::SoftStep
                                                ? std::span<const StageStep>(kSoftStepStages)
                                                : std::span<const StageStep>(kSequentialImpulseStages);
  for (const StageStep& stage : stages) {
    stage.run(d, dt, stats);
    stats.seconds[stage.stage] = clock.Lap();
    stats.seconds.ran[static_cast<std::size_t>(stage.stage)] = true;
  }

  for (const double seconds : stats.seconds.byStage) stats.seconds.total += seconds;
#if defined(TALUS_VALIDATE)
  // The validation pass (world/world_validate.h), outside the timed stages.
  AbortIfInvalid(CheckStep(d, stats));
#endif
  return stats;
}

}  // namespace talus
