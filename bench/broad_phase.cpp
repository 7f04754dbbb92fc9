// Broad phase benchmarks: uniform grid, AABB tree and brute force on worlds
// of 100 to 100k bodies, uniform and mixed sizes, dense, sparse and on the
// benchmark-scene floor (docs/bench-scenes.md), static and moving; plus tiny worlds for the brute-force
// crossover. One iteration is one step: Update(proxies) then FindPairs.
// Counters: candidate pairs, pairs after the sphere test, oversized tests.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "collision/broad_phase.h"

namespace talus {
namespace {

// SplitMix64 (docs/bench-scenes.md), so the worlds are the same everywhere.
struct Rng {
  std::uint64_t state;
  double Uniform() {
    state += 0x9E3779B97F4A7C15ull;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
};

enum class Scene {
  Uniform,  ///< 1 m cubes' spheres (r 0.866), 8 m^3 of space per body: a dense pile
  Mixed,    ///< radii log-uniform 0.05 to 5 m, 60 m^3 per body
  Sparse,   ///< radii log-uniform 0.05 to 5 m, 20000 m^3 per body
  Floor,    ///< the benchmark scenes' floor under layers of cubes, 1 m apart horizontally
};

struct World {
  std::vector<BroadPhaseProxy> proxies;
  std::vector<Vec3> velocity;
  double halfExtent = 0.0;
};

World MakeWorld(Scene scene, int n) {
  Rng rng{static_cast<std::uint64_t>(n) * 7919u + static_cast<std::uint64_t>(scene)};
  World w;
  const double perBody = scene == Scene::Uniform ? 8.0 : scene == Scene::Mixed ? 60.0 : 20000.0;
  w.halfExtent = 0.5 * std::cbrt(perBody * n);
  if (scene == Scene::Floor) {
    w.proxies.push_back({.sphere = {Vec3(0, -1, 0), std::sqrt(50.0 * 50 + 1 + 50.0 * 50)}, .isStatic = true});
    w.velocity.push_back(Vec3::Zero());
  }
  const int side = static_cast<int>(std::ceil(std::sqrt(n / 4.0)));
  for (int i = static_cast<int>(w.proxies.size()); i < n; ++i) {
    BroadPhaseProxy p;
    if (scene == Scene::Floor) {
      // Layers of side x side cubes, 1.1 m apart, stacked 1.1 m apart.
      const int layer = i / (side * side);
      const int k = i % (side * side);
      p.sphere = {Vec3(1.1 * (k % side) - 0.55 * side, 0.5 + 1.1 * layer, 1.1 * (k / side) - 0.55 * side),
                  std::sqrt(3.0) / 2};
      w.halfExtent = 0.55 * side;
    } else {
      const double h = w.halfExtent;
      const double radius =
          scene == Scene::Uniform ? std::sqrt(3.0) / 2 : 0.05 * std::pow(100.0, rng.Uniform());
      p.sphere = {Vec3(rng.Uniform(-h, h), rng.Uniform(-h, h), rng.Uniform(-h, h)), radius};
    }
    w.proxies.push_back(p);
    // About 3 m/s at 60 Hz.
    w.velocity.push_back(0.05 * Vec3(rng.Uniform(-1, 1), rng.Uniform(-1, 1), rng.Uniform(-1, 1)));
  }
  return w;
}

// Moves every dynamic body one step, bouncing off the world's box.
void Move(World& w) {
  for (std::size_t i = 0; i < w.proxies.size(); ++i) {
    BroadPhaseProxy& p = w.proxies[i];
    if (p.isStatic) continue;
    p.sphere.center += w.velocity[i];
    for (int a = 0; a < 3; ++a) {
      if (std::abs(p.sphere.center[a]) > w.halfExtent + 2.0) w.velocity[i][a] = -w.velocity[i][a];
    }
  }
}

void RunSteps(benchmark::State& state, BroadPhase& phase, World& world, bool moving) {
  std::vector<BroadPhasePair> pairs;
  BroadPhaseStats stats;
  // One untimed step first: the tree's initial build and the buffers' growth
  // are not the steady state a world runs in.
  if (!phase.Update(world.proxies)) state.SkipWithError("proxy refused");
  phase.FindPairs(pairs, stats);
  for (auto _ : state) {
    if (moving) Move(world);
    if (!phase.Update(world.proxies)) state.SkipWithError("proxy refused");
    phase.FindPairs(pairs, stats);
    benchmark::DoNotOptimize(pairs.data());
  }
  state.counters["candidates"] = static_cast<double>(stats.candidatePairs);
  state.counters["sphere_pairs"] = static_cast<double>(stats.spherePairs);
  state.counters["oversized_tests"] = static_cast<double>(stats.oversizedTests);
  state.counters["cells"] = static_cast<double>(stats.occupiedCells);
  state.counters["bodies_per_s"] = benchmark::Counter(static_cast<double>(world.proxies.size()),
                                                      benchmark::Counter::kIsIterationInvariantRate);
}

// Args: kind, scene, bodies, moving.
void BM_BroadPhase(benchmark::State& state) {
  const auto kind = static_cast<BroadPhaseKind>(state.range(0));
  const auto scene = static_cast<Scene>(state.range(1));
  World world = MakeWorld(scene, static_cast<int>(state.range(2)));
  BroadPhase phase(kind);
  // The structure itself, even at 100 bodies (BM_TinyWorld measures the
  // tiny-world path's crossover).
  phase.SetTinyWorldProxies(0);
  state.SetLabel(std::string(ToString(kind)) +
                 (scene == Scene::Uniform  ? "/uniform"
                  : scene == Scene::Mixed  ? "/mixed"
                  : scene == Scene::Sparse ? "/sparse"
                                           : "/floor") +
                 (state.range(3) != 0 ? "/moving" : "/static"));
  RunSteps(state, phase, world, state.range(3) != 0);
}

void BroadPhaseArgs(benchmark::internal::Benchmark* b) {
  for (const int kind : {0, 1, 2}) {
    for (const int scene : {0, 1, 2, 3}) {
      for (const int n : {100, 1000, 10000, 100000}) {
        // Brute force is O(n^2): 10k bodies is already 50M tests a step.
        if (kind == static_cast<int>(BroadPhaseKind::BruteForce) && n > 10000) continue;
        for (const int moving : {0, 1}) b->Args({kind, scene, n, moving});
      }
    }
  }
}
BENCHMARK(BM_BroadPhase)->Apply(BroadPhaseArgs)->Unit(benchmark::kMicrosecond);

// Tiny worlds with the tiny-world path off: where the structures overtake
// brute force (sets kTinyWorldProxies). Args: kind, bodies.
void BM_TinyWorld(benchmark::State& state) {
  const auto kind = static_cast<BroadPhaseKind>(state.range(0));
  World world = MakeWorld(Scene::Uniform, static_cast<int>(state.range(1)));
  BroadPhase phase(kind);
  phase.SetTinyWorldProxies(0);
  state.SetLabel(ToString(kind));
  RunSteps(state, phase, world, true);
}
BENCHMARK(BM_TinyWorld)
    ->ArgsProduct({{0, 1, 2}, {2, 4, 8, 16, 32, 64, 128, 256, 512}})
    ->Unit(benchmark::kNanosecond);

}  // namespace
}  // namespace talus

BENCHMARK_MAIN();
