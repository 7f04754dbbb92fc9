// The full-size reference scenes through Talus with its defaults (label
// `slow`: Release only). Criteria from SCENES.md: pyramid H = 15 stands
// (drift < 0.05 m between steps 120 and 600); hull_pile L = 10 settles with
// no body escaping.
#include <gtest/gtest.h>

#include "talus/harness/bench_run.h"
#include "talus/reference/body_mass.h"
#include "talus/reference/talus_backend.h"

namespace talus::harness {
namespace {

BenchReport RunTalus(std::string_view scene, int parameter) {
  BackendRegistry registry;
  reference::RegisterTalusBackends(registry);
  auto report = RunBenchScene(registry, "talus", *FindBenchScene(scene), parameter, kBenchDefaultSteps);
  EXPECT_TRUE(report.Ok()) << report.GetError().message;
  return report.Ok() ? report.Value() : BenchReport{};
}

TEST(FullScenes, TalusPyramidOfHeightFifteenStands) {
  const BenchReport report = RunTalus("pyramid", 15);
  EXPECT_EQ(report.bodies, 1240);
  ASSERT_TRUE(report.drift.has_value());
  EXPECT_LT(*report.drift, 0.05);
}

TEST(FullScenes, TalusHullPileOfSideTenSettlesWithNothingEscaping) {
  const BenchReport report = RunTalus("hull_pile", 10);
  EXPECT_EQ(report.bodies, 1000);
  ASSERT_TRUE(report.escaped.has_value());
  EXPECT_EQ(*report.escaped, 0);
  // Settled: kinetic energy below that of the whole pile moving at 1 cm/s.
  double totalMass = 0.0;
  const Scenario scene = MakeHullPileScene(10).Value();
  for (const BodySpec& body : scene.bodies) {
    if (body.motion == Motion::Dynamic) totalMass += reference::ComputeBodyMass(body).Value().mass;
  }
  const double settledEnergy = 0.5 * totalMass * 0.01 * 0.01;
  ASSERT_TRUE(report.kineticEnergy.has_value());
  EXPECT_LT(*report.kineticEnergy, settledEnergy) << "total mass " << totalMass << " kg";
  // 5 cm: a tenth of a hull's size; deeper means bodies sink into each other.
  ASSERT_TRUE(report.maxPenetration.has_value());
  EXPECT_LT(*report.maxPenetration, 0.05);
}

}  // namespace
}  // namespace talus::harness
