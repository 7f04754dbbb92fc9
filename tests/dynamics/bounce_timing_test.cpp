// Bounces timed inside the step (MethodSettings::bounceTiming =
// TimeOfImpact, dynamics/bounce_timing.h): the time of impact and the
// reflected flight against their closed forms, then whole worlds against
// the analytic apex e^(2k) H of a ball dropped from H, a resting ball that
// must not bounce, and a head-on collision of two balls (momentum kept,
// relative speed times e).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "dynamics/bounce_timing.h"
#include "talus/world.h"

namespace talus {
namespace bounce_timing_test {

constexpr double kG = 9.81;
constexpr double kH = 1.0 / 60.0;

TEST(TimeBounce, ImpactTimeAndSpeedSolveTheFlight) {
  // g(t*) = 0 and g'(t*) = -speed, for approaches that hit at several
  // fractions of the step, with and without gravity, and pushed apart.
  struct Case {
    double gap, speed, acceleration;
  };
  for (const Case c : {Case{0.05, -4.0, -kG}, Case{0.001, -4.0, -kG}, Case{0.066, -4.0, -kG},
                       Case{0.01, -1.0, 0.0}, Case{0.03, -2.0, 3.0}}) {
    const TimedBounce b = TimeBounce(c.gap, c.speed, c.acceleration, kH, 0.7, 0.01);
    ASSERT_TRUE(b.hits) << c.gap << " " << c.speed;
    ASSERT_GE(b.time, 0.0);
    ASSERT_LE(b.time, kH);
    const double t = b.time;
    // Round-off of the gap polynomial at these magnitudes: ~1e-16 of 0.1 m.
    EXPECT_NEAR(c.gap + c.speed * t + 0.5 * c.acceleration * t * t, 0.0, 1e-15);
    EXPECT_NEAR(c.speed + c.acceleration * t, -b.speed, 1e-14);
    // The rest of the step on the reflected flight.
    const double rest = kH - t;
    EXPECT_NEAR(b.endSpeed, 0.7 * b.speed + c.acceleration * rest, 1e-14);
    EXPECT_NEAR(b.endGap, 0.7 * b.speed * rest + 0.5 * c.acceleration * rest * rest, 1e-16);
  }
}

TEST(TimeBounce, PenetrationTimesTheImpactInTheLastStep) {
  // A ball falling at 4 m/s found 3 cm inside the floor crossed it
  // 3 cm / 4 m/s (with gravity's correction) ago: t* < 0, and the flight
  // from there is h - t* long.
  const TimedBounce b = TimeBounce(-0.03, -4.0, -kG, kH, 0.5, 0.5);
  ASSERT_TRUE(b.hits);
  EXPECT_LT(b.time, 0.0);
  EXPECT_NEAR(-0.03 - 4.0 * b.time - 0.5 * kG * b.time * b.time, 0.0, 1e-15);
  EXPECT_NEAR(b.speed, std::sqrt(16.0 - 2.0 * kG * 0.03), 1e-14);
  const double rest = kH - b.time;
  EXPECT_NEAR(b.endGap, 0.5 * b.speed * rest - 0.5 * kG * rest * rest, 1e-16);
}

TEST(TimeBounce, NoBounceWhereNoneHappensThisStep) {
  // Misses the step: 10 cm away at 1 m/s. The later landing's impact
  // speed is still given (1 m/s: nothing accelerates it), so a caller can
  // tell that it will bounce.
  const TimedBounce later = TimeBounce(0.1, -1.0, 0.0, kH, 0.7, 0.5);
  EXPECT_FALSE(later.hits);
  EXPECT_EQ(later.speed, 1.0);
  // Rising and never pulled back, or penetrating and already leaving.
  EXPECT_FALSE(TimeBounce(0.001, 1.0, 0.0, kH, 0.7, 0.5).hits);
  EXPECT_FALSE(TimeBounce(-0.001, 1.0, -kG, kH, 0.7, 0.5).hits);
  // Resting: the impact speed g h is below the threshold.
  EXPECT_FALSE(TimeBounce(0.0, -kG * kH, -kG, kH, 0.7, 0.5).hits);
  // Deeper than a step of approach explains: not timed, and said so (0.2 m
  // at 2 m/s was crossed 0.1 s ago; 0.5 m under gravity never was).
  for (const double depth : {0.2, 0.5}) {
    const TimedBounce deep = TimeBounce(-depth, -2.0, -kG, kH, 0.7, 0.5);
    EXPECT_FALSE(deep.hits);
    EXPECT_TRUE(deep.tooDeep) << depth;
  }
}

TEST(TimeBounce, ARelandingWithinTheStepEndsOnTheSurface) {
  // Rebound 0.05 m/s under gravity: back down after 10 ms, inside the rest
  // of a 1/60 s step that began at the surface. And a point 0.1 mm up,
  // rising at 2 cm/s: gravity brings it down after 7 ms (the root for
  // u0 >= 0), at 4.9 cm/s, and its rebound lands again within the step.
  for (const TimedBounce& b :
       {TimeBounce(0.0, -0.1, -kG, kH, 0.5, 0.01), TimeBounce(1e-4, 0.02, -kG, kH, 0.7, 0.01)}) {
    ASSERT_TRUE(b.hits);
    EXPECT_EQ(b.endGap, 0.0);
    EXPECT_GE(b.endSpeed, 0.0);
  }
  const TimedBounce rising = TimeBounce(1e-4, 0.02, -kG, kH, 0.7, 0.01);
  EXPECT_NEAR(1e-4 + 0.02 * rising.time - 0.5 * kG * rising.time * rising.time, 0.0, 1e-17);
  EXPECT_NEAR(rising.speed, std::sqrt(0.02 * 0.02 + 2.0 * kG * 1e-4), 1e-15);
}

// World with a static floor (top at y = 0) and a ball of radius 0.1 m.
struct BallScene {
  World world;
  BodyId ball;
};

BallScene DropBall(double height, double e, const WorldSettings& settings) {
  BallScene scene{World::Create(settings).Value(), {}};
  EXPECT_TRUE(scene.world.CreateBody({.type = BodyType::Static,
                                      .position = {0, -0.5, 0},
                                      .shape = Shape::CreateBox({5, 0.5, 5}).Value(),
                                      .restitution = 0.0}));
  scene.ball = scene.world
                   .CreateBody({.type = BodyType::Dynamic,
                                .position = {0, height + 0.1, 0},
                                .shape = Shape::CreateSphere(0.1).Value(),
                                .density = 1000.0,
                                .restitution = e})
                   .Value();
  return scene;
}

WorldSettings BounceSettings() {
  WorldSettings s;
  s.gravity = {0.0, -kG, 0.0};
  s.sleeping = false;
  s.restitutionCombine = RestitutionCombine::Max;
  s.methods.bounceTiming = BounceTiming::TimeOfImpact;
  s.methods.translation = TranslationIntegrator::ExactConstantAcceleration;
  return s;
}

// The apex of the ball's lowest point after each of its first `count`
// bounces, from the state of the first step that leaves the floor rising:
// free flight from there is a parabola (ExactConstantAcceleration follows it
// to round-off), so the apex is y + vy^2 / (2 g), exact, not the sampled
// maximum (which at 1/60 s misses it by up to g h^2 / 8 = 0.34 mm).
std::vector<double> Apexes(BallScene& scene, int count, double h) {
  std::vector<double> apexes;
  bool rising = false;
  for (int n = 0; n < static_cast<int>(20.0 / h) && static_cast<int>(apexes.size()) < count; ++n) {
    EXPECT_TRUE(scene.world.Step(h));
    const BodyState s = scene.world.GetBodyState(scene.ball).Value();
    const double vy = s.linearVelocity.y();
    if (!rising && vy > 0.0) {
      rising = true;
      apexes.push_back(s.position.y() - 0.1 + vy * vy / (2.0 * kG));
    } else if (rising && vy < 0.0) {
      rising = false;
    }
  }
  return apexes;
}

TEST(TimedBounces, BallApexesAreRestitutionSquaredPowersOfTheDrop) {
  // Drop heights put the impact at different fractions of a 1/60 s step
  // (1 m: 0.52 of a step past a boundary after the 27th; 0.37 m and 1.513 m
  // elsewhere), and each later bounce falls at its own fraction.
  for (const double e : {0.5, 0.7, 0.9}) {
    for (const double height : {1.0, 0.37, 1.513}) {
      for (const double h : {kH, 1.0 / 30.0, 1.0 / 240.0}) {
        BallScene scene = DropBall(height, e, BounceSettings());
        // Bounces whose impact speed e^(k-1) sqrt(2 g H) clears the 0.5 m/s
        // threshold at all (0.2% above it, far above round-off), at most 4:
        // e = 0.5 from 1 m lands a fourth time at 0.55 m/s, after a flight
        // whose last step starts 14.6 mm up at 1/30 s; a speculative row
        // asking h vn of that step stopped it on the surface at 0.44 m/s.
        int count = 0;
        while (count < 4 && std::pow(e, count) * std::sqrt(2.0 * kG * height) > 0.501) ++count;
        const std::vector<double> apexes = Apexes(scene, count, h);
        ASSERT_EQ(static_cast<int>(apexes.size()), count) << "e " << e << " H " << height << " h " << h;
        for (int k = 1; k <= count; ++k) {
          const double expected = std::pow(e, 2 * k) * height;
          // Issue 15's goal is 0.5%; the scheme is exact for a ball on a
          // face under constant gravity (impact time, reflected flight and
          // the free flights all closed forms), so round-off is all that
          // is left: 1e-9 relative, far below the 0.5%.
          EXPECT_NEAR(apexes[static_cast<std::size_t>(k - 1)], expected, 1e-9 * expected)
              << "e " << e << " H " << height << " h " << h << " bounce " << k;
        }
      }
    }
  }
}

TEST(TimedBounces, FlatBoxApexesAreRestitutionSquaredPowersOfTheDrop) {
  // A 0.4 m cube landing flat: four points bounce at once, their velocity
  // rows solved as a block, their position rows (equalities with the same
  // target) by Gauss-Seidel sweeps, which agree at once. Exact as the
  // ball (measured 1e-13 relative): 1e-9 relative.
  for (const double e : {0.5, 0.9}) {
    for (const double height : {1.0, 0.37}) {
      World world = World::Create(BounceSettings()).Value();
      ASSERT_TRUE(world.CreateBody({.type = BodyType::Static,
                                    .position = {0, -0.5, 0},
                                    .shape = Shape::CreateBox({5, 0.5, 5}).Value()}));
      BallScene scene{std::move(world), {}};
      scene.ball = scene.world
                       .CreateBody({.type = BodyType::Dynamic,
                                    .position = {0, height + 0.2, 0},
                                    .shape = Shape::CreateBox({0.2, 0.2, 0.2}).Value(),
                                    .density = 500.0,
                                    .restitution = e})
                       .Value();
      const std::vector<double> apexes = Apexes(scene, 2, kH);
      ASSERT_EQ(apexes.size(), 2u);
      for (int k = 1; k <= 2; ++k) {
        // Apexes() measures the centre less 0.1 m; the cube's bottom is 0.2 m below it.
        const double apex = apexes[static_cast<std::size_t>(k - 1)] - 0.1;
        const double expected = std::pow(e, 2 * k) * height;
        EXPECT_NEAR(apex, expected, 1e-9 * expected) << "e " << e << " H " << height << " bounce " << k;
      }
      EXPECT_LT(scene.world.GetBodyState(scene.ball).Value().angularVelocity.norm(), 1e-9);
    }
  }
}

TEST(TimedBounces, StepBoundaryBouncesMissTheApexByAStepOfTravel) {
  // The write-up's timing, for contrast: the first apex of a 1 m drop at
  // 1/60 s errs by more than the 0.5% above (it is found up to v h = 7 cm
  // from the surface), so the test above can fail.
  WorldSettings s = BounceSettings();
  s.methods.bounceTiming = BounceTiming::StepBoundary;
  BallScene scene = DropBall(1.0, 0.7, s);
  const std::vector<double> apexes = Apexes(scene, 1, kH);
  ASSERT_EQ(apexes.size(), 1u);
  EXPECT_GT(std::abs(apexes[0] - 0.49), 0.005 * 0.49);
}

TEST(TimedBounces, RestingBallDoesNotJitter) {
  // A ball resting on the floor with e = 0.9: every step's impact speed is
  // g h = 0.16 m/s, below the threshold, so nothing bounces and the ball
  // stays put. Resting tolerance: the speculative rows hold it at its
  // contact within round-off (no Baumgarte push: depth <= 0).
  for (const double h : {kH, 1.0 / 240.0}) {
    WorldSettings s = BounceSettings();
    BallScene scene = DropBall(0.0, 0.9, s);
    std::int64_t timed = 0;
    for (int n = 0; n < static_cast<int>(3.0 / h); ++n) {
      const StepStatistics stats = scene.world.Step(h).Value();
      timed += stats.timedBounces;
      const BodyState state = scene.world.GetBodyState(scene.ball).Value();
      ASSERT_NEAR(state.position.y(), 0.1, 1e-6) << "step " << n;
      ASSERT_LT(std::abs(state.linearVelocity.y()), 1e-6) << "step " << n;
    }
    EXPECT_EQ(timed, 0);
  }
}

TEST(TimedBounces, HeadOnBallsKeepMomentumAndReflectTheRelativeSpeed) {
  // Two free balls (no gravity) of 1 and 3 times the mass closing at 5 m/s:
  // Newton's restitution law, v2' - v1' = -e (v2 - v1), and momentum kept.
  // The impact falls inside a step at every h used.
  for (const double e : {0.3, 0.8}) {
    for (const double h : {kH, 1.0 / 47.0}) {
      WorldSettings s = BounceSettings();
      s.gravity = Vec3::Zero();
      World world = World::Create(s).Value();
      const Shape ball = Shape::CreateSphere(0.1).Value();
      const BodyId a = world
                           .CreateBody({.type = BodyType::Dynamic,
                                        .position = {-0.5, 0, 0},
                                        .linearVelocity = {3.0, 0, 0},
                                        .shape = ball,
                                        .density = 1000.0,
                                        .restitution = e})
                           .Value();
      const BodyId b = world
                           .CreateBody({.type = BodyType::Dynamic,
                                        .position = {0.5, 0, 0},
                                        .linearVelocity = {-2.0, 0, 0},
                                        .shape = ball,
                                        .density = 3000.0,
                                        .restitution = e})
                           .Value();
      const double ma = world.GetBodyState(a).Value().mass;
      const double mb = world.GetBodyState(b).Value().mass;
      const double before = ma * 3.0 - mb * 2.0;
      for (int n = 0; n < static_cast<int>(0.5 / h); ++n) ASSERT_TRUE(world.Step(h));
      const BodyState sa = world.GetBodyState(a).Value();
      const BodyState sb = world.GetBodyState(b).Value();
      // Momentum: every impulse acts on both with opposite signs; round-off
      // of a few additions of ~20 N s.
      EXPECT_NEAR(ma * sa.linearVelocity.x() + mb * sb.linearVelocity.x(), before, 1e-12 * ma * 5.0);
      // Restitution: 5 m/s closing becomes 5 e opening, exactly (the row's
      // target), to the solver's round-off.
      EXPECT_NEAR(sb.linearVelocity.x() - sa.linearVelocity.x(), 5.0 * e, 1e-9) << "e " << e << " h " << h;
      // Position: the balls left each other at the time of impact, so their
      // centres are 0.2 m + 5 e (t - t*) apart, t* = 0.8 m / 5 m/s.
      const double t = static_cast<int>(0.5 / h) * h;
      EXPECT_NEAR(sb.position.x() - sa.position.x(), 0.2 + 5.0 * e * (t - 0.16), 1e-9)
          << "e " << e << " h " << h;
    }
  }
}

TEST(TimedBounces, AnUnknownBounceTimingIsRefusedByName) {
  WorldSettings s;
  s.methods.bounceTiming = static_cast<BounceTiming>(7);
  const auto world = World::Create(s);
  ASSERT_FALSE(world);
  EXPECT_NE(world.GetError().message.find("WorldSettings.methods.bounceTiming = 7 is not a BounceTiming"),
            std::string::npos)
      << world.GetError().message;
  EXPECT_EQ(ValidateSettings(BounceSettings()), "");
}

}  // namespace bounce_timing_test
}  // namespace talus
