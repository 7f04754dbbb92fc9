// Hull building: Talus's Quickhull against qhull on the same point sets.
//
// Two shapes (uniform in the unit ball, where most points are discarded
// early, and on the unit sphere, where every point is a hull vertex) at 1e3,
// 1e5 and 1e6 points. Each set is generated once from a fixed seed, so both
// builders see identical input and runs are comparable. Report the median of
// repetitions: --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <map>
#include <random>
#include <utility>
#include <vector>

#include "talus/hull_builder.h"
#include "talus/reference/qhull_oracle.h"

namespace talus {
namespace {

enum class Shape { kBall = 0, kSphere = 1 };

// Points from a fixed seed: a Gaussian direction (uniform on the sphere),
// scaled by the cube root of a uniform variate for the ball.
std::vector<Vec3> MakePoints(Shape shape, int count) {
  std::mt19937_64 rng(20240601u + static_cast<unsigned>(count));
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<Vec3> points;
  points.reserve(static_cast<std::size_t>(count));
  while (static_cast<int>(points.size()) < count) {
    Vec3 d(gauss(rng), gauss(rng), gauss(rng));
    const double length = d.norm();
    if (length < 1e-12) continue;
    d /= length;
    if (shape == Shape::kBall) d *= std::cbrt(uniform(rng));
    points.push_back(d);
  }
  return points;
}

// The point sets, built on first use and shared by both builders.
const std::vector<Vec3>& Points(Shape shape, int count) {
  static std::map<std::pair<int, int>, std::vector<Vec3>> cache;
  auto key = std::make_pair(static_cast<int>(shape), count);
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, MakePoints(shape, count)).first;
  return it->second;
}

void TalusBuild(benchmark::State& state) {
  const auto& points = Points(static_cast<Shape>(state.range(0)), static_cast<int>(state.range(1)));
  for (auto _ : state) {
    auto hull = BuildHull(points);
    if (!hull) state.SkipWithError(hull.GetError().message.c_str());
    benchmark::DoNotOptimize(hull);
  }
  state.SetItemsProcessed(state.iterations() * state.range(1));
}

void QhullBuild(benchmark::State& state) {
  const auto& points = Points(static_cast<Shape>(state.range(0)), static_cast<int>(state.range(1)));
  for (auto _ : state) {
    auto hull = QhullConvexHull(points, {.computeVolume = false});
    if (!hull) state.SkipWithError(hull.GetError().message.c_str());
    benchmark::DoNotOptimize(hull);
  }
  state.SetItemsProcessed(state.iterations() * state.range(1));
}

void Sizes(benchmark::internal::Benchmark* b) {
  b->ArgNames({"sphere", "n"});
  for (int shape : {0, 1}) {
    for (int count : {1000, 100000, 1000000}) b->Args({shape, count});
  }
  b->Unit(benchmark::kMillisecond);
}

BENCHMARK(TalusBuild)->Apply(Sizes);
BENCHMARK(QhullBuild)->Apply(Sizes);

}  // namespace
}  // namespace talus

BENCHMARK_MAIN();
