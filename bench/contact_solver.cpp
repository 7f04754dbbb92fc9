// The contact solver on the reference pyramid (its specification:
// docs/bench-scenes.md): the scalar Sequential Impulses against the
// coloured wide solver (MethodSettings::contactOrder), per step and per
// stage. Google Benchmark's time is the thread's CPU time, which a busy
// shared machine disturbs far less than wall-clock time; the stage
// counters are StepStatistics' wall-clock seconds per step, in ms. Speed
// only; the physics is the tests' and the testbed's business.
#include <benchmark/benchmark.h>

#include "talus/world.h"

namespace talus {
namespace {

constexpr double kH = 1.0 / 60.0;

// The `pyramid` scene of height `h` (docs/bench-scenes.md): layer i holds
// the unit-half-extent cubes j, k in [i / 2, h - (i + 1) / 2) at x = -h + 2j
// + (i odd), y = 1 + 2.5 i, z likewise, friction 0.2, density 1000, on a
// static floor box whose top is y = 0; sleeping off, as the testbed runs
// it. Stepped `settle` steps before timing.
World MakePyramid(int h, ContactOrder kind, int settle) {
  WorldSettings settings;
  settings.sleeping = false;
  settings.methods.contactOrder = kind;
  // The per-point friction rows both orders have (the coloured solver has
  // no coupled block), so the two differ by their order alone.
  settings.methods.frictionSolve = FrictionSolve::PerPoint;
  settings.timeStages = true;  // the per-stage counters below read StepStatistics::seconds
  World world = World::Create(settings).Value();
  (void)world.CreateBody({.type = BodyType::Static,
                          .position = {0.0, -1.0, 0.0},
                          .shape = Shape::CreateBox({50.0, 1.0, 50.0}).Value(),
                          .friction = 0.2});
  const Shape cube = Shape::CreateBox(Vec3::Constant(1.0)).Value();
  for (int i = 0; i < h; ++i) {
    const double shift = i % 2 == 1 ? 1.0 : 0.0;
    for (int j = i / 2; j < h - (i + 1) / 2; ++j) {
      for (int k = i / 2; k < h - (i + 1) / 2; ++k) {
        (void)world.CreateBody({.type = BodyType::Dynamic,
                                .position = {-h + 2.0 * j + shift, 1.0 + 2.5 * i, -h + 2.0 * k + shift},
                                .shape = cube,
                                .density = 1000.0,
                                .friction = 0.2});
      }
    }
  }
  for (int n = 0; n < settle; ++n) (void)world.Step(kH);
  return world;
}

// Arguments: pyramid height, ContactOrder (0 sequential, 1 coloured
// wide), steps before timing (120: the layers have landed).
void BM_PyramidStep(benchmark::State& state) {
  World world = MakePyramid(static_cast<int>(state.range(0)), static_cast<ContactOrder>(state.range(1)),
                            static_cast<int>(state.range(2)));
  StageTimes sum;
  StepStatistics last;
  for (auto _ : state) {
    last = world.Step(kH).Value();
    for (const StageInfo& stage : kStages) sum[stage.stage] += last.seconds[stage.stage];
    sum.total += last.seconds.total;
  }
  const double perStepMs = 1e3 / static_cast<double>(state.iterations());
  state.counters["broad_phase_ms"] = sum[Stage::UpdateBroadPhase] * perStepMs;
  state.counters["find_contacts_ms"] = sum[Stage::FindContacts] * perStepMs;
  state.counters["prepare_ms"] = sum[Stage::PrepareContacts] * perStepMs;
  state.counters["velocities_ms"] = sum[Stage::SolveVelocities] * perStepMs;
  state.counters["scatter_store_ms"] = sum[Stage::ScatterAndStoreImpulses] * perStepMs;
  state.counters["total_ms"] = sum.total * perStepMs;
  state.counters["points"] = last.contactPoints;
  state.counters["colours"] = last.solverColours;
  state.counters["overflow"] = last.overflowPairs;
  state.counters["sweeps"] = last.velocitySweeps;
}
BENCHMARK(BM_PyramidStep)
    ->Args({15, 0, 120})
    ->Args({15, 1, 120})
    ->Args({10, 0, 120})
    ->Args({10, 1, 120})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(60);

}  // namespace
}  // namespace talus

BENCHMARK_MAIN();
