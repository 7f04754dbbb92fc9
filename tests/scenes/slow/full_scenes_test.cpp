// The full-size hull_pile scene through Talus with its defaults (label
// `slow`: Release only). Criterion from docs/bench-scenes.md: no body's centre ends
// below y = 0 or outside the walls ("must be 0"), plus a penetration bound.
// docs/bench-scenes.md gives the final kinetic energy as a figure ("a settled pile is
// near 0") without a threshold, so it is printed, not asserted; the measured
// values are in docs/bench-scenes.md. The full-size pyramid is checked by
// tests/slow/pyramid_test.cpp through talus::World directly.
#include <gtest/gtest.h>

#include <cstdio>

#include "talus/harness/scenes/bench_run.h"
#include "talus/reference/talus_backend.h"
#include "talus/world_settings.h"

namespace talus::harness {
namespace full_scenes_test {

BenchReport RunTalus(std::string_view scene, int parameter) {
  BackendRegistry registry;
  reference::RegisterTalusBackends(registry);
  auto report = RunBenchScene(registry, "talus", *FindBenchScene(scene), parameter, kBenchDefaultSteps);
  EXPECT_TRUE(report.Ok()) << report.GetError().message;
  return report.Ok() ? report.Value() : BenchReport{};
}

TEST(FullScenes, TalusHullPileOfSideTenKeepsEveryBodyInside) {
  const BenchReport report = RunTalus("hull_pile", 10);
  EXPECT_EQ(report.bodies, 1000);
  ASSERT_TRUE(report.escaped.has_value());
  EXPECT_EQ(*report.escaped, 0);
  ASSERT_TRUE(report.kineticEnergy.has_value());
  std::printf("hull_pile 10 at step %d: kinetic energy %.3f J, max penetration %.4f m\n", kBenchDefaultSteps,
              *report.kineticEnergy, report.maxPenetration.value_or(-1.0));
  // The Baumgarte bias pushes only depth beyond the slop, so a resting
  // contact settles at the slop (4 mm, WorldSettings::slop); a contact the
  // velocity solve failed to hold for a whole step sinks at most one step of
  // free fall, g h^2 (2.7 mm at 1/60 s), deeper. Issue 15: with single-point
  // edge contacts the pile ended at 1.6-4.1 cm; persistent points hold it
  // at the slop (5.0 mm with the 5 mm slop before it became 4 mm).
  ASSERT_TRUE(report.maxPenetration.has_value());
  const double gravity = 9.81;
  EXPECT_LE(*report.maxPenetration, talus::WorldSettings{}.slop + gravity * kBenchTimeStep * kBenchTimeStep);
}

}  // namespace full_scenes_test
}  // namespace talus::harness
