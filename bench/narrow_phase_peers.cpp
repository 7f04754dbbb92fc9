// Narrow-phase queries per second, Talus against its peers on the same
// pairs: each SAT mode (Full, GaussMapPruned, pruned + per-pair cache) with
// the clipped manifold, libccd's GJK intersect, MPR penetration and GJK+EPA
// penetration, and Bullet's btGjkPairDetector (GJK + btGjkEpa penetration
// solver) and btGjkEpaSolver2, for random hulls of 8, 32 and 128 vertices
// (points on a unit sphere), separated by 0.05 m, touching (overlapping
// by 0.01 m, a resting contact) or deep (overlapping by 0.3 of their
// reach). Every method answers the full question it is built
// for (Talus: verdict, normal, depth and manifold). The uncached Talus
// methods call the public pair query (talus/pair_query.h), as a user
// would; the cached one needs the per-pair SatCache only the World's
// dispatch (collision/collide.h) takes.
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <vector>

#include "collision/collide.h"
#include "collision/narrow_phase_scratch.h"
#include "talus/hull_builder.h"
#include "talus/pair_query.h"
#include "talus/reference/bullet_narrow_phase.h"
#include "talus/reference/ccd_oracle.h"

namespace talus {
namespace {

enum class Method {
  Full,
  Pruned,
  PrunedCached,
  CcdGjk,
  CcdMpr,
  CcdGjkEpa,
  BulletPairDetector,
  BulletGjkEpa2
};

const char* Name(Method m) {
  switch (m) {
    case Method::Full:
      return "talus-full";
    case Method::Pruned:
      return "talus-pruned";
    case Method::PrunedCached:
      return "talus-pruned-cached";
    case Method::CcdGjk:
      return "ccd-gjk-intersect";
    case Method::CcdMpr:
      return "ccd-mpr-penetration";
    case Method::CcdGjkEpa:
      return "ccd-gjk-penetration";
    case Method::BulletPairDetector:
      return "bullet-gjk-pair-detector";
    case Method::BulletGjkEpa2:
      return "bullet-gjkepa2";
  }
  return "unknown";
}

Shape SphereHull(int vertices, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Vec3> points;
  for (int i = 0; i < vertices; ++i)
    points.push_back(Vec3(normal(rng), normal(rng), normal(rng)).normalized());
  return Shape::CreateHull(std::make_shared<const Hull>(BuildHull(points).Value())).Value();
}

// range(0): vertices; range(1): 0 separated, 1 deep, 2 touching; range(2):
// Method.
void BM_NarrowPhasePeers(benchmark::State& state) {
  const Shape a = SphereHull(static_cast<int>(state.range(0)), 1);
  const Shape b = SphereHull(static_cast<int>(state.range(0)), 2);
  const auto method = static_cast<Method>(state.range(2));
  state.SetLabel(Name(method));
  const Transform xfA{};
  Transform xfB{.position = Vec3(0.0, 0.1, 0.05),
                .rotation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()))};
  const double reach = a.Support(Vec3::UnitX()).x() -
                       (xfB.rotation * b.Support(xfB.rotation.conjugate() * -Vec3::UnitX())).x();
  constexpr double kGap = 0.05;          // metres, separated pairs
  constexpr double kTouchDepth = 0.01;   // metres past first contact, touching pairs
  constexpr double kDeepFraction = 0.7;  // of the reach, deep pairs
  if (state.range(1) == 0) {
    xfB.position.x() = reach + kGap;
  } else if (state.range(1) == 1) {
    xfB.position.x() = kDeepFraction * reach;
  } else {
    // First contact along x by bisection on libccd's verdict (the y and z
    // offsets keep it below `reach`), then pushed in by kTouchDepth.
    double inside = kDeepFraction * reach;
    double outside = reach + kGap;
    for (int i = 0; i < 60; ++i) {
      xfB.position.x() = 0.5 * (inside + outside);
      const bool hit = reference::CcdGjkIntersect({.hull = &a.GetHull(), .transform = xfA},
                                                  {.hull = &b.GetHull(), .transform = xfB})
                           .intersecting;
      (hit ? inside : outside) = xfB.position.x();
    }
    xfB.position.x() = inside - kTouchDepth;
  }

  const NarrowPhaseSettings settings{
      .satMode = method == Method::Full ? SatMode::Full : SatMode::GaussMapPruned,
      .manifoldMode = ManifoldMode::Clipped,
      .useSatCache = method == Method::PrunedCached};
  SatCache cache;
  ContactManifold manifold{};
  NarrowPhaseScratch scratch;  // as the step's: one per thread, kept across queries
  const reference::CcdObject ccdA{.hull = &a.GetHull(), .transform = xfA};
  const reference::CcdObject ccdB{.hull = &b.GetHull(), .transform = xfB};
  const reference::BulletHullShape bulletA(a.GetHull());
  const reference::BulletHullShape bulletB(b.GetHull());
  bool intersecting = false;
  for (auto _ : state) {
    switch (method) {
      case Method::Full:
      case Method::Pruned:
        intersecting = CollideShapes(a, xfA, b, xfB, settings).Value().touching;
        break;
      case Method::PrunedCached:
        intersecting = Collide(a, xfA, b, xfB, settings, &cache, nullptr, &manifold, &scratch);
        break;
      case Method::CcdGjk:
        intersecting = reference::CcdGjkIntersect(ccdA, ccdB).intersecting;
        break;
      case Method::CcdMpr:
        intersecting = reference::CcdMprPenetration(ccdA, ccdB).intersecting;
        break;
      case Method::CcdGjkEpa:
        intersecting = reference::CcdGjkPenetration(ccdA, ccdB).intersecting;
        break;
      case Method::BulletPairDetector:
        intersecting = reference::BulletPairQuery(bulletA, xfA, bulletB, xfB,
                                                  reference::BulletNarrowPhaseMethod::GjkPairDetector)
                           .intersecting;
        break;
      case Method::BulletGjkEpa2:
        intersecting = reference::BulletPairQuery(bulletA, xfA, bulletB, xfB,
                                                  reference::BulletNarrowPhaseMethod::GjkEpa2)
                           .intersecting;
        break;
    }
    // An int, not the bool: DoNotOptimize on a bool let GCC read back a
    // register with stray upper bits as the bool's value.
    int verdict = intersecting ? 1 : 0;
    benchmark::DoNotOptimize(verdict);
  }
  if (intersecting != (state.range(1) != 0)) state.SkipWithError("pair is not in the intended state");
  state.counters["queries/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

BENCHMARK(BM_NarrowPhasePeers)
    ->ArgNames({"vertices", "overlap", "method"})
    ->ArgsProduct({{8, 32, 128}, {0, 2, 1}, {0, 1, 2, 3, 4, 5, 6, 7}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace talus

BENCHMARK_MAIN();
