// World::Step on stacked and piled boxes: what one step of the whole
// pipeline costs, and what the solver options (iterations, warm starting,
// split impulses) and sleeping change. Speed only; accuracy is the tests'
// and the testbed's business.
#include <benchmark/benchmark.h>

#include <cmath>

#include "talus/world.h"

namespace talus {
namespace {

// A grid of `columns` x `columns` columns of `height` unit boxes on a
// ground box, stepped one second first so contacts are warm.
World MakeStacks(int columns, int height, const WorldSettings& settings) {
  World world = World::Create(settings).Value();
  const Shape box = Shape::CreateBox(Vec3::Constant(0.5)).Value();
  (void)world.CreateBody({.type = BodyType::Static,
                          .position = {0, -0.5, 0},
                          .shape = Shape::CreateBox({100, 0.5, 100}).Value()});
  for (int cx = 0; cx < columns; ++cx) {
    for (int cz = 0; cz < columns; ++cz) {
      for (int i = 0; i < height; ++i) {
        (void)world.CreateBody({.type = BodyType::Dynamic,
                                .position = {2.0 * cx, i + 0.5, 2.0 * cz},
                                .shape = box,
                                .density = 1000.0});
      }
    }
  }
  for (int n = 0; n < 60; ++n) (void)world.Step(1.0 / 60.0);
  return world;
}

void BM_StepStacks(benchmark::State& state) {
  WorldSettings settings;
  settings.sleeping = false;
  settings.velocityIterations = static_cast<int>(state.range(1));
  World world = MakeStacks(static_cast<int>(state.range(0)), 5, settings);
  for (auto _ : state) benchmark::DoNotOptimize(world.Step(1.0 / 60.0));
  state.counters["bodies"] = world.BodyCount();
}
BENCHMARK(BM_StepStacks)
    ->Args({2, 10})
    ->Args({4, 10})
    ->Args({8, 10})
    ->Args({4, 40})
    ->Unit(benchmark::kMicrosecond);

void BM_StepStacksOptions(benchmark::State& state) {
  WorldSettings settings;
  settings.sleeping = false;
  settings.methods.warmStarting = state.range(0) != 0;
  settings.methods.positionCorrection = static_cast<PositionCorrection>(state.range(1));
  World world = MakeStacks(4, 5, settings);
  for (auto _ : state) benchmark::DoNotOptimize(world.Step(1.0 / 60.0));
}
// Arguments: warm starting (0/1), PositionCorrection (0 Baumgarte, 1 split
// impulses). The non-linear Gauss-Seidel sweeps this once listed as 2 were
// retired (docs/dynamics.md, "Retired options"), and World::Create refuses
// that value.
BENCHMARK(BM_StepStacksOptions)->Args({1, 0})->Args({0, 0})->Args({1, 1})->Unit(benchmark::kMicrosecond);

// Sleeping: the same stacks after they fell asleep cost only the broad phase.
void BM_StepSleepingStacks(benchmark::State& state) {
  World world = MakeStacks(4, 5, WorldSettings{});
  for (int n = 0; n < 120; ++n) (void)world.Step(1.0 / 60.0);
  for (auto _ : state) benchmark::DoNotOptimize(world.Step(1.0 / 60.0));
}
BENCHMARK(BM_StepSleepingStacks)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace talus

BENCHMARK_MAIN();
