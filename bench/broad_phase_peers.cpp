// Broad phase against Bullet's: Talus's uniform grid, AABB tree and brute
// force, and Bullet's btDbvtBroadphase, on the same bodies: 100 to 100k
// bounding spheres, uniform sizes (1 m cubes' spheres, 8 m^3 of space per
// body) or mixed (radii log-uniform 0.05-5 m, 60 m^3 per body), static or
// moving (about 3 m/s at 60 Hz, bouncing in the world's box). One iteration
// is one step: Talus Update + FindPairs; Bullet setAabb on every proxy (the
// sphere's box) + calculateOverlappingPairs. Counters: the pairs at each
// filter (Talus: candidates, sphere pairs; Bullet: AABB pairs).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "collision/broad_phase.h"
#include "talus/reference/bullet_broad_phase.h"

namespace talus {
namespace {

// SplitMix64, so the worlds are the same on every machine.
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

struct Bodies {
  std::vector<BroadPhaseProxy> proxies;
  std::vector<Sphere> spheres;
  std::vector<Vec3> velocity;
  double halfExtent = 0.0;
};

Bodies MakeBodies(bool mixed, int n) {
  Rng rng{static_cast<std::uint64_t>(n) * 7919u + (mixed ? 1u : 0u)};
  Bodies w;
  w.halfExtent = 0.5 * std::cbrt((mixed ? 60.0 : 8.0) * n);
  for (int i = 0; i < n; ++i) {
    const double h = w.halfExtent;
    const double radius = mixed ? 0.05 * std::pow(100.0, rng.Uniform()) : std::sqrt(3.0) / 2;
    const Sphere s{Vec3(rng.Uniform(-h, h), rng.Uniform(-h, h), rng.Uniform(-h, h)), radius};
    w.proxies.push_back({.sphere = s, .isStatic = false, .active = true});
    w.spheres.push_back(s);
    w.velocity.push_back(0.05 * Vec3(rng.Uniform(-1, 1), rng.Uniform(-1, 1), rng.Uniform(-1, 1)));
  }
  return w;
}

void Move(Bodies& w) {
  for (std::size_t i = 0; i < w.spheres.size(); ++i) {
    Vec3& c = w.spheres[i].center;
    c += w.velocity[i];
    for (int a = 0; a < 3; ++a) {
      if (std::abs(c[a]) > w.halfExtent + 2.0) w.velocity[i][a] = -w.velocity[i][a];
    }
    w.proxies[i].sphere.center = c;
  }
}

// Args: structure (0 grid, 1 tree, 2 brute force, 3 Bullet DBVT), mixed, bodies, moving.
void BM_BroadPhasePeers(benchmark::State& state) {
  const int structure = static_cast<int>(state.range(0));
  const bool mixed = state.range(1) != 0;
  const bool moving = state.range(3) != 0;
  Bodies bodies = MakeBodies(mixed, static_cast<int>(state.range(2)));
  state.SetLabel(
      std::string(structure == 3 ? "bullet_dbvt" : ToString(static_cast<BroadPhaseKind>(structure))) +
      (mixed ? "/mixed" : "/uniform") + (moving ? "/moving" : "/static"));
  if (structure == 3) {
    const std::unique_ptr<bool[]> isStatic(new bool[bodies.spheres.size()]());
    reference::BulletDbvtBroadPhase bullet(bodies.spheres, {isStatic.get(), bodies.spheres.size()});
    std::int64_t pairs = 0;
    for (auto _ : state) {
      if (moving) Move(bodies);
      pairs = bullet.Step(bodies.spheres);
      benchmark::DoNotOptimize(pairs);
    }
    state.counters["aabb_pairs"] = static_cast<double>(pairs);
  } else {
    BroadPhase phase(static_cast<BroadPhaseKind>(structure));
    std::vector<BroadPhasePair> pairs;
    BroadPhaseStats stats;
    for (auto _ : state) {
      if (moving) Move(bodies);
      if (!phase.Update(bodies.proxies)) state.SkipWithError("proxy refused");
      phase.FindPairs(pairs, stats);
      benchmark::DoNotOptimize(pairs.data());
    }
    state.counters["candidates"] = static_cast<double>(stats.candidatePairs);
    state.counters["sphere_pairs"] = static_cast<double>(stats.spherePairs);
  }
  state.counters["bodies_per_s"] = benchmark::Counter(static_cast<double>(bodies.spheres.size()),
                                                      benchmark::Counter::kIsIterationInvariantRate);
}

void PeerArgs(benchmark::internal::Benchmark* b) {
  for (const int structure : {0, 1, 2, 3}) {
    for (const int mixed : {0, 1}) {
      for (const int n : {100, 1000, 10000, 100000}) {
        if (structure == 2 && n > 10000) continue;  // O(n^2)
        for (const int moving : {0, 1}) b->Args({structure, mixed, n, moving});
      }
    }
  }
}
BENCHMARK(BM_BroadPhasePeers)->Apply(PeerArgs)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace talus

BENCHMARK_MAIN();
