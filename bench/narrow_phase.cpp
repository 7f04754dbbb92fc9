// SAT queries per second between two random convex hulls of 8, 32 and 128
// vertices (points on a unit sphere, so every point is a vertex), for pairs
// that overlap and pairs that are separated, in the Full and GaussMapPruned
// modes and with the per-pair cache (GaussMapPruned + SatCache, the cache
// filled by the previous query as in a resting scene).
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <vector>

#include "collision/narrow_phase_scratch.h"
#include "collision/sat.h"
#include "talus/hull_builder.h"

namespace talus {
namespace {

std::shared_ptr<const Hull> SphereHull(int vertices, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Vec3> points;
  for (int i = 0; i < vertices; ++i)
    points.push_back(Vec3(normal(rng), normal(rng), normal(rng)).normalized());
  return std::make_shared<const Hull>(BuildHull(points).Value());
}

// range(0): vertices per hull; range(1): 1 overlapping, 0 separated;
// range(2): 0 Full, 1 GaussMapPruned, 2 GaussMapPruned + cache.
void BM_Sat(benchmark::State& state) {
  const auto a = SphereHull(static_cast<int>(state.range(0)), 1);
  const auto b = SphereHull(static_cast<int>(state.range(0)), 2);
  // Along x, B touches A at `contact`: overlap by moving B to 0.7 of it, or
  // leave a 0.05 m gap.
  const Transform xfB{.position = Vec3(0.0, 0.1, 0.05),
                      .rotation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()))};
  const PosedHull pa = PosedHull::Make(*a, {.position = Vec3::Zero(), .rotation = Quat::Identity()});
  const PosedHull atOrigin = PosedHull::Make(*b, xfB);
  const double contact = pa.SupportDistance(Vec3::UnitX(), 0) + atOrigin.SupportDistance(-Vec3::UnitX(), 0);
  Transform placed = xfB;
  placed.position.x() = state.range(1) ? 0.7 * contact : contact + 0.05;
  const PosedHull pb = PosedHull::Make(*b, placed);
  const SatMode mode = state.range(2) == 0 ? SatMode::Full : SatMode::GaussMapPruned;
  const bool cached = state.range(2) == 2;
  SatCache cache;
  NarrowPhaseStats stats;
  NarrowPhaseScratch scratch;  // as the step's: one per thread, kept across queries
  bool separated = false;
  for (auto _ : state) {
    const SatResult result = RunSat(pa, pb, mode, 0.0, cached ? &cache : nullptr, &stats, &scratch);
    separated = result.separated;
    benchmark::DoNotOptimize(result);
  }
  if (separated == (state.range(1) == 1)) state.SkipWithError("pair is not in the intended state");
  state.counters["queries/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["axes/query"] =
      static_cast<double>(stats.faceAxesTested + stats.edgeAxesTested) / static_cast<double>(stats.satTests);
  state.counters["pruned/query"] =
      static_cast<double>(stats.edgePairsPruned) / static_cast<double>(stats.satTests);
}

BENCHMARK(BM_Sat)
    ->ArgNames({"vertices", "overlap", "mode"})
    ->ArgsProduct({{8, 32, 128}, {1, 0}, {0, 1, 2}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace talus

BENCHMARK_MAIN();
