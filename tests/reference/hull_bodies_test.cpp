// The peers handle hull bodies: the body frame of the scenario (where the
// points are written) is not the centre of mass nor the principal frame, so
// each backend must shift to the centroid and turn to the principal axes and
// report states back in the scenario's frame. The expected centroid and
// inertia come from the engine's own geometry (BuildHull and
// ComputeMassProperties), independent of reference/common's triangulation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "talus/harness/analytic/hull_rest_analysis.h"
#include "talus/harness/backend/backend.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/hull_builder.h"
#include "talus/mass_properties.h"
#include "talus/reference/bullet_backend.h"
#include "talus/reference/ode_backend.h"

#include "peer_fixture.h"

namespace talus::reference {
namespace hull_bodies_test {

using harness::Backend;
using test::Build;

harness::Run HullRun() { return test::LoadRun("stacking/hull_rest.json"); }

MassProperties HullMass(const harness::BodySpec& body) {
  const auto& points = std::get<harness::HullShape>(body.shape).points;
  auto hull = BuildHull(points);
  EXPECT_TRUE(hull);
  auto mass = ComputeMassProperties(hull.Value(), body.density);
  EXPECT_TRUE(mass);
  return mass.Value();
}

class HullBodies : public ::testing::TestWithParam<std::string> {};

TEST_P(HullBodies, StartStateHasTheHullsCentroidMassAndInertia) {
  const harness::Run run = HullRun();
  auto backend = Build(GetParam(), run);
  ASSERT_TRUE(backend);
  const harness::BodySpec& spec = run.scenario.bodies[1];
  const MassProperties mass = HullMass(spec);
  const harness::BodyReading state = backend->GetBodyState(1);
  const Mat3 rotation = spec.orientation.toRotationMatrix();
  // Two exact integrations of the same solid agree to round-off; 1e-9
  // relative leaves room for the engines' own quaternion normalisation.
  EXPECT_LT((state.origin - spec.position).norm(), 1e-9);
  EXPECT_LT((state.centerOfMass - (spec.position + rotation * mass.centerOfMass)).norm(), 1e-9);
  EXPECT_LT(state.orientation.angularDistance(spec.orientation), 1e-9);
  EXPECT_NEAR(state.mass, mass.mass, 1e-9 * mass.mass);
  const Mat3 expected = rotation * mass.inertia * rotation.transpose();
  EXPECT_LT((state.worldInertia - expected).norm(), 1e-9 * expected.norm()) << state.worldInertia;
}

TEST_P(HullBodies, SpinningHullTurnsAboutItsCentreOfMass) {
  harness::Run run = HullRun();
  // Alone, without gravity, spinning about a skew axis: the centre of mass
  // must stay put while the body frame turns around it.
  run.scenario.world.gravity = Vec3::Zero();
  run.scenario.bodies.erase(run.scenario.bodies.begin());
  run.scenario.truths.clear();
  run.scenario.bodies[0].angularVelocity = Vec3(0.3, 2.0, -0.5);
  auto backend = Build(GetParam(), run);
  ASSERT_TRUE(backend);
  const Vec3 centroid = HullMass(run.scenario.bodies[0]).centerOfMass;
  const Vec3 start = backend->GetBodyState(0).centerOfMass;
  for (int n = 0; n < 60; ++n) backend->Step();
  const harness::BodyReading state = backend->GetBodyState(0);
  // The centre of mass does not move (round-off over 60 steps ~1e-14 m) and
  // the reported origin sits at -centroid from it in the turned frame.
  EXPECT_LT((state.centerOfMass - start).norm(), 1e-9);
  EXPECT_LT((state.origin - (state.centerOfMass - state.orientation * centroid)).norm(), 1e-9);
  // The body has turned (by ~2 rad): the check above is not vacuous.
  EXPECT_GT(state.orientation.angularDistance(run.scenario.bodies[0].orientation), 1.0);
}

// What each peer reaches on hull_rest.json, measured, with the reason.
struct RestLimits {
  double height = 0.0;  ///< metres, largest |centre of mass height - (analytic + offset)|
  double speed = 0.0;   ///< m/s, largest speed left at the end
  double offset = 0.0;  ///< metres the engine's margin holds the hull above the analytic height
};
RestLimits HullRestLimits(const std::string& backend) {
  // Bullet tuned shrinks the hull by its 1 mm margin before the margin is
  // added back, so it rests at the geometric height: measured -0.007 mm.
  // A quarter of the margin (0.25 mm) is far above that resting depth and
  // fails a hull left grown by the margin (+1.000 mm before the shrink).
  // Its defaults inflate the hull by the 4 cm default margin: measured
  // +40.0 mm, so 40 mm +- 3 mm.
  if (backend == "bullet-tuned") return {0.25 * kBulletCollisionMargin, 0.01};
  if (backend == "bullet") return {0.003, 0.01, 0.04};
  // ODE: -0.7 mm for a box on the box ground (box_rest) but -34 mm here and
  // -12 mm for a cube written as a hull, still rocking at ~8 cm/s after 4 s
  // with "LCP internal error" messages: its convex-box collider
  // gives one contact point per step instead of a face patch, so the hull
  // rocks on it, sunk in the ground. A frame or centroid error would be off
  // by the 0.3 m / 0.2 m shift of the points and fail this all the same.
  return {0.04, 0.2};
}

TEST_P(HullBodies, HullComesToRestOnItsBottomFaceAtTheAnalyticHeight) {
  const harness::Run run = HullRun();
  auto backend = Build(GetParam(), run);
  ASSERT_TRUE(backend);
  for (int n = 0; n < run.steps; ++n) backend->Step();
  const auto analysis =
      harness::AnalyseHullRest(std::get<harness::HullShape>(run.scenario.bodies[1].shape).points);
  ASSERT_TRUE(analysis);
  const harness::HullRestFace& bottom = analysis.Value().faces[analysis.Value().NearestFace(Vec3(0, -1, 0))];
  const harness::BodyReading state = backend->GetBodyState(1);
  const RestLimits limits = HullRestLimits(GetParam());
  EXPECT_NEAR(state.centerOfMass.y(), bottom.height + limits.offset, limits.height);
  // Resting flat on that face: measured < 0.015 rad in every peer.
  const Vec3 normal = state.orientation * bottom.normal;
  EXPECT_LT(std::acos(std::clamp(-normal.y(), -1.0, 1.0)), 0.05);
  EXPECT_LT(state.linearVelocity.norm(), limits.speed);
}

TEST(BulletTunedHull, RefusesAHullThinnerThanTwiceTheMarginItIsShrunkBy) {
  harness::Run run = HullRun();
  // A slab 1.5 mm thick: shrinking each face by the 1 mm margin would empty
  // it, so the tuned configuration names the body; the defaults, which do
  // not shrink, build it.
  run.scenario.bodies[1].shape = harness::HullShape{
      {Vec3(0, 0, 0), Vec3(0.5, 0, 0), Vec3(0, 0, 0.5), Vec3(0.5, 0, 0.5), Vec3(0, 0.0015, 0),
       Vec3(0.5, 0.0015, 0), Vec3(0, 0.0015, 0.5), Vec3(0.5, 0.0015, 0.5)}};
  auto tuned = test::PeerRegistry().Create("bullet-tuned", run);
  ASSERT_FALSE(tuned);
  EXPECT_NE(
      tuned.GetError().message.find("bullet: body \"hull\": the hull is too thin to shrink by the 0.001 m"),
      std::string::npos)
      << tuned.GetError().message;
  EXPECT_TRUE(test::PeerRegistry().Create("bullet", run));
}

INSTANTIATE_TEST_SUITE_P(Peers, HullBodies, ::testing::ValuesIn(test::BulletAndOdePeers()),
                         test::PeerTestName);

}  // namespace hull_bodies_test
}  // namespace talus::reference
