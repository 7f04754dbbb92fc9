// Friction scenes the friction solvers' tests share (coupled_block_test.cpp,
// manifold_friction_test.cpp): a cube sliding to a stop on static ground, a
// cube on a slope, and the discrete Coulomb stop distance they are judged by.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <initializer_list>
#include <string>
#include <vector>

#include "contact_scene.h"
#include "talus/world.h"

namespace talus::friction_scenes {

constexpr double kG = 9.81;

inline WorldSettings Settings(FrictionSolve friction, int iterations) {
  WorldSettings settings;
  settings.sleeping = false;
  settings.velocityIterations = iterations;
  settings.positionIterations = iterations;
  settings.methods.frictionSolve = friction;
  return settings;
}

inline Shape Box(const Vec3& half) { return Shape::CreateBox(half).Value(); }

// The static ground the scenes stand on, its top face at y = 0.
inline void AddGround(World& world, double mu) {
  EXPECT_TRUE(world.CreateBody(
      {.type = BodyType::Static, .position = {0, -0.5, 0}, .shape = Box({20, 0.5, 20}), .friction = mu}));
}

// A 0.5 m cube of 500 kg/m^3 (62.5 kg) at `position`, moving.
inline BodyId AddCube(World& world, const Vec3& position, const Vec3& velocity, const Vec3& spin, double mu) {
  return world
      .CreateBody({.type = BodyType::Dynamic,
                   .position = position,
                   .linearVelocity = velocity,
                   .angularVelocity = spin,
                   .shape = Box(Vec3::Constant(0.25)),
                   .density = 500.0,
                   .friction = mu})
      .Value();
}

struct Stop {
  double distance = 0.0;   ///< m along x when the box first stops
  double lateral = 0.0;    ///< m, |z| then
  double restSpeed = 0.0;  ///< m/s, |v| + |w| ten steps after the stop
};

// A 0.5 m cube launched along +x on the ground, stepped until it first
// stops (|vx| < 1e-6 m/s), then ten steps more.
inline Stop SlideAndStop(const WorldSettings& settings, double v0, double mu, double h) {
  World world = World::Create(settings).Value();
  AddGround(world, mu);
  const BodyId box = AddCube(world, {0, 0.25, 0}, {v0, 0, 0}, Vec3::Zero(), mu);
  Stop stop;
  for (int n = 0; n < 1000; ++n) {
    EXPECT_TRUE(world.Step(h));
    const BodyState s = world.GetBodyState(box).Value();
    if (std::abs(s.linearVelocity.x()) < 1e-6) {
      stop.distance = s.position.x();
      stop.lateral = std::abs(s.position.z());
      break;
    }
  }
  for (int n = 0; n < 10; ++n) EXPECT_TRUE(world.Step(h));
  const BodyState s = world.GetBodyState(box).Value();
  stop.restSpeed = s.linearVelocity.norm() + s.angularVelocity.norm();
  return stop;
}

// The discrete Coulomb stop: each step friction removes mu g h of speed and
// a body contact impulses act on moves by h v(n+1), so the box stops after
// K = floor(v0 / (mu g h)) moving steps at x = h sum_{k=1..K} (v0 - k mu g h)
// (the exact sum the testbed's sliding_stop truth compares with).
inline double DiscreteStopDistance(double v0, double mu, double h) {
  const double loss = mu * kG * h;
  const int steps = static_cast<int>(std::floor(v0 / loss));
  double x = 0.0;
  for (int k = 1; k <= steps; ++k) x += h * (v0 - k * loss);
  return x;
}

// A cube released at rest on a static slope of `angle` (rad) with friction
// mu; returns its displacement along the slope after `steps` steps of h.
inline double SlopeDisplacement(const WorldSettings& settings, double angle, double mu, double h, int steps) {
  World world = World::Create(settings).Value();
  const Quat tilt(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
  EXPECT_TRUE(world.CreateBody({.type = BodyType::Static,
                                .position = tilt * Vec3(0, -0.5, 0),
                                .orientation = tilt,
                                .shape = Box({20, 0.5, 20}),
                                .friction = mu}));
  const Vec3 start = tilt * Vec3(0, 0.25, 0);
  const BodyId box = world
                         .CreateBody({.type = BodyType::Dynamic,
                                      .position = start,
                                      .orientation = tilt,
                                      .shape = Box(Vec3::Constant(0.25)),
                                      .density = 500.0,
                                      .friction = mu})
                         .Value();
  for (int n = 0; n < steps; ++n) EXPECT_TRUE(world.Step(h));
  const Vec3 moved = world.GetBodyState(box).Value().position - start;
  return moved.dot(tilt * Vec3(-1, 0, 0));  // down the slope (it rises along +x)
}

// The impulses a step stored on `body`'s contacts (what next step warm
// starts from), summed: their force (N s), their moment about `centre`
// (N m s) and the number of points.
struct StoredImpulses {
  Vec3 force = Vec3::Zero();
  Vec3 moment = Vec3::Zero();
  int points = 0;
};

inline StoredImpulses SumStoredImpulses(const testing::ContactScene& scene, int body, const Vec3& centre) {
  StoredImpulses sum;
  for (const Contact& contact : scene.Contacts()) {
    const double sign = contact.bodyA == body ? 1.0 : (contact.bodyB == body ? -1.0 : 0.0);
    for (int i = 0; i < contact.manifold.pointCount; ++i) {
      const std::size_t si = static_cast<std::size_t>(i);
      const Vec3 impulse =
          sign * (contact.normalImpulse[si] * contact.manifold.normal + contact.frictionImpulse[si]);
      sum.force += impulse;
      sum.moment += (contact.manifold.points[si].position - centre).cross(impulse);
      ++sum.points;
    }
  }
  return sum;
}

// Sixteen cubes sliding and spinning into each other and to rest on the
// ground, two seconds at 60 Hz; every cube's final position and velocities
// in one list (for bit-identity over thread counts).
inline std::vector<double> SixteenCubesFinalState(const WorldSettings& settings) {
  World world = World::Create(settings).Value();
  AddGround(world, 0.6);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 16; ++i) {
    const double x = (i % 4) * 0.7;
    const double z = (i / 4) * 0.7;
    boxes.push_back(
        AddCube(world, {x, 0.25 + 0.6 * (i % 2), z}, {1.5 - x, 0, 1.0 - z}, {0, 0.5 * (i % 3), 0}, 0.6));
  }
  for (int n = 0; n < 120; ++n) EXPECT_TRUE(world.Step(1.0 / 60.0));
  std::vector<double> state;
  for (const BodyId id : boxes) {
    const BodyState s = world.GetBodyState(id).Value();
    for (int k = 0; k < 3; ++k) {
      state.push_back(s.position[k]);
      state.push_back(s.linearVelocity[k]);
      state.push_back(s.angularVelocity[k]);
    }
    state.push_back(s.orientation.w());
  }
  return state;
}

// Kinetic plus potential energy of `bodies` (J; height along +y, the
// scenes' gravity).
inline double TotalEnergy(const World& world, const std::vector<BodyId>& bodies) {
  double e = 0.0;
  for (const BodyId id : bodies) {
    const BodyState s = world.GetBodyState(id).Value();
    const Mat3 rotation = s.orientation.toRotationMatrix();
    const Mat3 inertia = rotation * s.localInertia * rotation.transpose();
    e += 0.5 * s.mass * s.linearVelocity.squaredNorm() +
         0.5 * s.angularVelocity.dot(inertia * s.angularVelocity) + s.mass * kG * s.position.y();
  }
  return e;
}

// World::Create refuses `settings` with a message that names every one of
// `parts` (the settings involved).
inline void ExpectRefusedNaming(const WorldSettings& settings, std::initializer_list<const char*> parts) {
  const auto refused = World::Create(settings);
  ASSERT_FALSE(refused);
  for (const char* part : parts) {
    EXPECT_NE(refused.GetError().message.find(part), std::string::npos) << refused.GetError().message;
  }
}

// SixteenCubesFinalState under `settings` at 1, 2 and 3 threads: the same
// bits (Prepare builds the rows on the pool).
inline void ExpectSixteenCubesBitIdenticalForAnyThreadCount(const WorldSettings& settings) {
  std::vector<std::vector<double>> runs;
  for (const int threads : {1, 2, 3}) {
    WorldSettings threaded = settings;
    threaded.threads = threads;
    runs.push_back(SixteenCubesFinalState(threaded));
  }
  for (std::size_t r = 1; r < runs.size(); ++r) {
    ASSERT_EQ(runs[r].size(), runs[0].size());
    EXPECT_EQ(std::memcmp(runs[r].data(), runs[0].data(), runs[0].size() * sizeof(double)), 0)
        << "threads run " << r;
  }
}

}  // namespace talus::friction_scenes
