// The benchmark scenes (docs/bench-scenes.md: the pyramid and the hull
// pile, built exactly as talus-scenes builds them) as Google Benchmarks:
// one iteration is a whole run of kBenchDefaultSteps steps, timed by its
// steps alone (manual time: building the scene is left out), Talus beside
// Bullet's single-precision build in the same process, so a ratio is taken
// between figures of one run of this program. Talus's counters give its
// stage breakdown (each stage's mean ms a step, from StageTimes) and its
// longest step. Run with --benchmark_repetitions=3 and compare medians
// (docs/bench-scenes.md, "Google Benchmark of the step").
#include <benchmark/benchmark.h>

#include <string>
#include <string_view>

#include "talus/harness/scenes/bench_run.h"
#include "talus/harness/scenes/bench_scenes.h"
#include "talus/reference/all_backends.h"

namespace talus::scene_runs {

void BM_Scene(benchmark::State& state, std::string_view engine, std::string_view scene, int parameter) {
  const harness::BenchScene* found = harness::FindBenchScene(scene);
  if (found == nullptr) {
    state.SkipWithError("no such scene");
    return;
  }
  for (auto _ : state) {
    auto report = harness::RunBenchScene(reference::AllBackends(), engine, *found, parameter,
                                         harness::kBenchDefaultSteps);
    if (!report) {
      state.SkipWithError(report.GetError().message.c_str());
      return;
    }
    const harness::BenchReport& r = report.Value();
    state.SetIterationTime(r.totalMs / 1e3);
    state.counters["ms_per_step"] = r.msMean;
    state.counters["longest_step_ms"] = r.msMax;
    state.counters["bodies"] = r.bodies;
    state.counters["max_contacts"] = r.maxContacts;
    for (const harness::BenchStage& stage : r.stages) state.counters[stage.name + "_ms"] = stage.msMean;
  }
}

BENCHMARK_CAPTURE(BM_Scene, talus_pyramid_10, "talus", "pyramid", 10)
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Scene, bullet_f32_pyramid_10, "bullet-f32", "pyramid", 10)
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Scene, talus_hull_pile_10, "talus", "hull_pile", 10)
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Scene, bullet_f32_hull_pile_10, "bullet-f32", "hull_pile", 10)
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace talus::scene_runs

BENCHMARK_MAIN();
