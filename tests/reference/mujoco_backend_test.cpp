// The MuJoCo peer against analytic answers: free fall, the rest depth of
// MuJoCo's soft contact (derived from its solref/solimp below), the sliding
// stop, the combine rules it has to be told about, restitution's mapping,
// the settings it reports, determinism and clear errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "talus/harness/analytic/truths.h"
#include "talus/harness/backend/backend.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/harness/scenes/bench_scenes.h"
#include "talus/reference/body_mass.h"
#include "talus/reference/mujoco_backend.h"

#include "peer_fixture.h"

namespace talus::reference {
namespace mujoco_backend_test {

using harness::Backend;
using test::Build;
using test::LoadRun;

std::string SettingValue(const Backend& backend, const std::string& key) {
  for (const harness::Setting& setting : backend.Settings()) {
    if (setting.key == key) return setting.value;
  }
  return "(missing)";
}

// MuJoCo's soft contact at rest (mj_makeImpedance and the primal solver):
// each row obeys a = (1 - d) a0 + d aref with aref = -B v - K d r, where r
// is the contact's dist, K = 1 / (dmax^2 t^2) (solref (t, 1), t raised to
// 2h by refsafe), d(r) the solimp impedance, and the regulariser R =
// (1 - d) / d times MuJoCo's diagonal estimate (1/m for a normal row). With
// n symmetric contacts sharing the weight (a row's effective inverse masses
// sum to n/m), a = 0 and v = 0 give r = c (1 - d) g / (n d^2 K), c = 1 for
// an elliptic cone. A pyramidal cone carries the normal force on four edge
// rows n +- mu t whose common R is 2 mu^2 R0, R0 taken with the edge's
// diagonal (1 + mu^2)/m: the four rows in balance give c = mu^2 (1 + mu^2)/2
// (1 at mu = 1). Solved by fixed-point iteration (a contraction: d varies
// by 5% over the 1 mm solimp width).
double RestDist(int contacts, double mu, bool pyramidal, double g, double timeStep) {
  const double dmin = 0.9, dmax = 0.95, width = 0.001, midpoint = 0.5;  // solimp defaults, power 2
  const double t = std::max(kMujocoDefaultTimeConstant, 2.0 * timeStep);
  const double stiffness = 1.0 / (dmax * dmax * t * t);
  const double cone = pyramidal ? mu * mu * (1.0 + mu * mu) / 2.0 : 1.0;
  double r = 0.0;
  for (int i = 0; i < 200; ++i) {
    const double x = std::min(r / width, 1.0);
    const double y = x <= midpoint ? x * x / midpoint : 1.0 - (1.0 - x) * (1.0 - x) / (1.0 - midpoint);
    const double d = dmin + y * (dmax - dmin);
    r = cone * (1.0 - d) * g / (contacts * d * d * stiffness);
  }
  return r;
}

class MujocoProfiles : public ::testing::TestWithParam<std::string> {};

INSTANTIATE_TEST_SUITE_P(Mujoco, MujocoProfiles, ::testing::Values("mujoco", "mujoco-tuned"));

TEST(MujocoBackend, DefaultsFallOnTheSymplecticEulerSequence) {
  const harness::Run run = LoadRun("tumbling/box_free_fall.json");
  auto backend = Build("mujoco", run);
  ASSERT_TRUE(backend);
  const double y0 = backend->GetBodyState(0).centerOfMass.y();
  for (int n = 1; n <= run.steps; ++n) {
    backend->Step();
    // Euler updates v += h g, then x += h v: only round-off (~1e-14 m a
    // step) separates it from that sequence; the parabola is g h t / 2 =
    // 8 cm away after 1 s, so a wrong integrator cannot pass.
    ASSERT_NEAR(backend->GetBodyState(0).centerOfMass.y(),
                harness::FreeFallHeightSymplecticEuler(y0, 2.0, 9.81, run.timeStep, n), 1e-9)
        << "step " << n;
  }
}

TEST(MujocoBackend, TunedFallsOnTheParabolaWithRk4) {
  // A single body cannot touch anything, so the tuned configuration
  // integrates it with RK4, which is exact for a constant acceleration.
  const harness::Run run = LoadRun("tumbling/box_free_fall.json");
  auto backend = Build("mujoco-tuned", run);
  ASSERT_TRUE(backend);
  const double y0 = backend->GetBodyState(0).centerOfMass.y();
  for (int n = 1; n <= run.steps; ++n) {
    backend->Step();
    ASSERT_NEAR(backend->GetBodyState(0).centerOfMass.y(),
                harness::FreeFallHeight(y0, 2.0, 9.81, n * run.timeStep), 1e-9)
        << "step " << n;
  }
  EXPECT_NE(SettingValue(*backend, "integrator").find("RK4"), std::string::npos);
}

TEST_P(MujocoProfiles, SphereRestsAtTheSoftContactDepth) {
  // One contact through the centre: n = 1, and the sphere-box test reports
  // the true overlap as dist.
  harness::Run run = LoadRun("stacking/box_rest.json");
  run.scenario.bodies[1].shape = harness::SphereShape{0.5};
  auto backend = Build(GetParam(), run);
  ASSERT_TRUE(backend);
  for (int n = 0; n < run.steps; ++n) backend->Step();
  const bool pyramidal = GetParam() == "mujoco";
  const double expected = RestDist(1, run.scenario.bodies[1].friction, pyramidal, 9.81, run.timeStep);
  // About 1 mm of sinking; after 3 s at a 33 ms critically damped time
  // constant the transient is e^-90 of it, so 1e-7 m is left for the
  // solver's tolerance (1e-8 relative) and the pyramid's edge coupling.
  EXPECT_NEAR(0.5 - backend->GetBodyState(1).centerOfMass.y(), expected, 1e-7);
  const auto contacts = backend->GetContacts();
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_NEAR(contacts[0].depth, expected, 1e-7);
  // The normal points from B towards A (MuJoCo orders the sphere first).
  const harness::ContactReading& contact = contacts[0];
  const Vec3 fromBToA =
      backend->GetBodyState(contact.bodyA).centerOfMass - backend->GetBodyState(contact.bodyB).centerOfMass;
  EXPECT_NEAR(contact.normal.dot(fromBToA.normalized()), 1.0, 1e-9);
  EXPECT_NE(contact.bodyA, contact.bodyB);
}

TEST(MujocoBackend, BoxRestsAtTwiceTheReportedSoftContactDepth) {
  // The tuned (elliptic) box settles to 2e-9 m; the defaults' pyramidal
  // box keeps rocking by about 1e-5 m, which box_rest's jitter truth judges.
  const harness::Run run = LoadRun("stacking/box_rest.json");
  auto backend = Build("mujoco-tuned", run);
  ASSERT_TRUE(backend);
  for (int n = 0; n < run.steps; ++n) backend->Step();
  // Four corner contacts: n = 4. MuJoCo 2.2.2's box-box test places the
  // point midway through the overlap and reports dist as half of it
  // (measured), so the box sinks twice the equilibrium dist.
  const double dist = RestDist(4, run.scenario.bodies[1].friction, false, 9.81, run.timeStep);
  const auto contacts = backend->GetContacts();
  ASSERT_EQ(contacts.size(), 4u);
  for (const harness::ContactReading& contact : contacts) EXPECT_NEAR(contact.depth, dist, 1e-7);
  EXPECT_NEAR(0.5 - backend->GetBodyState(1).centerOfMass.y(), 2.0 * dist, 2e-7);
}

TEST_P(MujocoProfiles, SlidingBoxStopsWhereCoulombFrictionSays) {
  const harness::Run run = LoadRun("sliding/box_slide.json");  // mu 0.3, v0 1 (first sweep point)
  auto backend = Build(GetParam(), run);
  ASSERT_TRUE(backend);
  const harness::BodySpec& box = run.scenario.bodies[1];
  const double v0 = box.linearVelocity.x(), mu = box.friction;
  for (int n = 0; n < run.steps; ++n) backend->Step();
  const double distance = backend->GetBodyState(1).centerOfMass.x() - box.position.x();
  // The discrete answer of v -= mu g h, x += h v; MuJoCo's friction is
  // soft (regularised), so the box may stop up to one step earlier or later:
  // one step's travel at launch speed, v0 h.
  EXPECT_NEAR(distance, harness::SlidingStopDistanceSymplecticEuler(v0, mu, 9.81, run.timeStep),
              v0 * run.timeStep);
  EXPECT_NEAR(backend->GetBodyState(1).linearVelocity.norm(), 0.0, 1e-3);
}

TEST_P(MujocoProfiles, CombineRulesMuJoCoLacksComeFromExplicitPairs) {
  // Ground 0.8, box 0.3 under "min": the pair must slide on 0.3, where
  // MuJoCo's own max rule would stop it at 0.8 after 0.064 m.
  harness::Run run = LoadRun("sliding/box_slide.json");
  run.scenario.world.frictionCombine = harness::CombineRule::Min;
  run.scenario.bodies[0].friction = 0.8;
  run.scenario.bodies[1].friction = 0.3;
  auto backend = Build(GetParam(), run);
  ASSERT_TRUE(backend);
  EXPECT_EQ(SettingValue(*backend, "explicit contact pairs"), "1");
  const double v0 = run.scenario.bodies[1].linearVelocity.x();
  for (int n = 0; n < run.steps; ++n) backend->Step();
  EXPECT_NEAR(backend->GetBodyState(1).centerOfMass.x(),
              harness::SlidingStopDistanceSymplecticEuler(v0, 0.3, 9.81, run.timeStep), v0 * run.timeStep);
}

TEST(MujocoBackend, RestitutionMapsToTheDampingOfAHalfPeriodSpring) {
  // The spring-damper leaving at e v: exp(-z pi / sqrt(1 - z^2)) = e.
  for (double e = 0.05; e < 1.0; e += 0.05) {
    const double z = MujocoDampRatioForRestitution(e);
    EXPECT_NEAR(std::exp(-z * M_PI / std::sqrt(1.0 - z * z)), e, 1e-12) << e;
  }
  EXPECT_EQ(MujocoDampRatioForRestitution(0.0), 1.0);
  EXPECT_EQ(MujocoDampRatioForRestitution(1.0), 0.0);
  // e = 0 keeps MuJoCo's default; e > 0 keeps the default stiffness, the
  // time constant raised to two steps as MuJoCo's refsafe does.
  const MujocoSolref none = MujocoSolrefForRestitution(0.0, 0.001);
  EXPECT_EQ(none.first, 0.02);
  EXPECT_EQ(none.second, 1.0);
  const MujocoSolref fine = MujocoSolrefForRestitution(0.5, 0.001);
  EXPECT_DOUBLE_EQ(fine.first, -1.0 / (0.02 * 0.02));
  EXPECT_DOUBLE_EQ(fine.second, -2.0 * MujocoDampRatioForRestitution(0.5) / 0.02);
  const MujocoSolref coarse = MujocoSolrefForRestitution(0.5, 0.05);
  EXPECT_DOUBLE_EQ(coarse.first, -1.0 / (0.1 * 0.1));
}

TEST(MujocoBackend, SettingsNameEveryOptionThatDiffersFromMuJoCosDefaults) {
  const harness::Run run = LoadRun("stacking/box_rest.json");
  auto defaults = Build("mujoco", run);
  auto tuned = Build("mujoco-tuned", run);
  ASSERT_TRUE(defaults && tuned);
  for (const std::string key : {"integrator", "friction cone", "solver", "solver tolerance",
                                "noslip iterations", "impratio", "multi-point convex collision (multiccd)"}) {
    EXPECT_NE(SettingValue(*defaults, key).find("(MuJoCo default)"), std::string::npos) << key;
  }
  EXPECT_EQ(SettingValue(*tuned, "friction cone"), "elliptic (MuJoCo default: pyramidal)");
  EXPECT_EQ(SettingValue(*tuned, "multi-point convex collision (multiccd)"), "on (MuJoCo default: off)");
  EXPECT_EQ(SettingValue(*tuned, "impratio"), "10 (MuJoCo default: 1)");
  EXPECT_EQ(SettingValue(*tuned, "solver tolerance"), "1e-10 (MuJoCo default: 1e-08)");
  EXPECT_EQ(SettingValue(*tuned, "noslip iterations"), "10 (MuJoCo default: 0 (off))");
  EXPECT_NE(SettingValue(*tuned, "integrator").find("(MuJoCo default)"), std::string::npos);
  EXPECT_EQ(SettingValue(*tuned, "time step (s)"), "0.016666666666666666");
  EXPECT_EQ(SettingValue(*tuned, "solver iterations"), "10 (the scenario's)");
  EXPECT_EQ(defaults->Name(), "mujoco");
  EXPECT_EQ(tuned->Name(), "mujoco-tuned");
}

TEST_P(MujocoProfiles, TwoRunsAreBitIdentical) {
  const harness::Run run = LoadRun("stacking/box_pyramid_4.json");
  auto first = Build(GetParam(), run);
  auto second = Build(GetParam(), run);
  ASSERT_TRUE(first && second);
  for (int n = 0; n < 120; ++n) {
    first->Step();
    second->Step();
  }
  for (int b = 0; b < first->BodyCount(); ++b) {
    const harness::BodyReading a = first->GetBodyState(b), c = second->GetBodyState(b);
    EXPECT_EQ(a.centerOfMass, c.centerOfMass) << b;
    EXPECT_EQ(a.orientation.coeffs(), c.orientation.coeffs()) << b;
    EXPECT_EQ(a.linearVelocity, c.linearVelocity) << b;
    EXPECT_EQ(a.angularVelocity, c.angularVelocity) << b;
  }
}

TEST_P(MujocoProfiles, HullFramesAndCentresOfMassLandWhereTheSceneSays) {
  const harness::Scenario scene = harness::MakeHullPileScene(2).Value();
  harness::Run run;
  run.scenario = scene;
  run.timeStep = scene.world.timeStep;
  auto backend = Build(GetParam(), run);
  ASSERT_TRUE(backend);
  for (int b = 0; b < 40; ++b) {
    const harness::BodySpec& body = scene.bodies[static_cast<size_t>(b)];
    const Vec3 centroid = ComputeBodyMass(body).Value().centroid;
    const harness::BodyReading state = backend->GetBodyState(b);
    // A few roundings of ~10 m coordinates through the principal rotation.
    EXPECT_LT((state.origin - body.position).norm(), 1e-12) << b;
    EXPECT_LT((state.centerOfMass - (body.position + centroid)).norm(), 1e-12) << b;
    EXPECT_LT(state.orientation.angularDistance(Quat::Identity()), 1e-12) << b;
  }
}

TEST(MujocoBackend, AWarningMidRunFailsTheWorldInsteadOfResettingIt) {
  // A box thrown at 1e12 m/s passes MuJoCo's mjMAXVAL (1e10) in qpos after
  // one step: MuJoCo warns (bad qpos) and silently resets the state to the
  // initial one. The backend must not hand that back as a result: the world
  // stops and every state is NaN, which fails the run.
  harness::Run run = LoadRun("tumbling/box_free_fall.json");
  run.scenario.bodies[0].linearVelocity = Vec3(1e12, 0.0, 0.0);
  auto backend = Build("mujoco", run);
  ASSERT_TRUE(backend);
  backend->Step();
  backend->Step();
  const harness::BodyReading state = backend->GetBodyState(0);
  EXPECT_TRUE(std::isnan(state.centerOfMass.x()));
  EXPECT_TRUE(std::isnan(state.linearVelocity.y()));
  EXPECT_TRUE(backend->GetContacts().empty());
}

TEST(MujocoBackend, RefusesWhatMuJoCoCannotDoWithTheReason) {
  harness::Run run = LoadRun("tumbling/box_torque_free.json");
  run.scenario.world.gyroscopic = false;
  auto noGyro = test::PeerRegistry().Create("mujoco", run);
  ASSERT_FALSE(noGyro);
  EXPECT_NE(noGyro.GetError().message.find("gyroscopic term off"), std::string::npos);

  harness::Run flat = LoadRun("stacking/hull_rest.json");
  auto& points = std::get<harness::HullShape>(flat.scenario.bodies[1].shape).points;
  for (Vec3& p : points) p.y() = 0.0;  // no volume
  auto degenerate = test::PeerRegistry().Create("mujoco-tuned", flat);
  ASSERT_FALSE(degenerate);
  EXPECT_EQ(degenerate.GetError().message.rfind("mujoco: ", 0), 0u) << degenerate.GetError().message;

  // pyramid H = 10: 385 cubes need far more than the mjData limit.
  harness::Run big;
  big.scenario = harness::MakePyramidScene(10).Value();
  big.timeStep = big.scenario.world.timeStep;
  auto tooBig = test::PeerRegistry().Create("mujoco", big);
  ASSERT_FALSE(tooBig);
  EXPECT_NE(tooBig.GetError().message.find("MB of mjData (nconmax 6260"), std::string::npos)
      << tooBig.GetError().message;
}

}  // namespace mujoco_backend_test
}  // namespace talus::reference
