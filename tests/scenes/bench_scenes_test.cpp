// The scene generators against the specification in docs/bench-scenes.md: counts,
// positions, materials, walls, the random stream, and the body-frame /
// centre-of-mass mapping each backend applies to the hull pile.
#include "talus/harness/scenes/bench_scenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <set>
#include <string>

#include "talus/harness/support/split_mix64.h"
#include "talus/reference/body_mass.h"
#include "talus/reference/bullet_backend.h"
#include "talus/reference/ode_backend.h"
#include "talus/reference/talus_backend.h"

namespace talus::harness {
namespace bench_scenes_test {

const Scenario& Pyramid15() {
  static const Scenario scene = MakePyramidScene(15).Value();
  return scene;
}

const Vec3& HalfExtents(const BodySpec& body) { return std::get<BoxShape>(body.shape).halfExtents; }

TEST(PyramidScene, HeightFifteenHas1240CubesThenTheFloor) {
  const Scenario& scene = Pyramid15();
  ASSERT_EQ(scene.bodies.size(), 1241u);
  EXPECT_EQ(PyramidCubeCount(15), 1240);
  for (int b = 0; b < 1240; ++b) {
    const BodySpec& cube = scene.bodies[static_cast<size_t>(b)];
    ASSERT_EQ(cube.motion, Motion::Dynamic) << b;
    EXPECT_EQ(HalfExtents(cube), Vec3::Ones()) << b;
    EXPECT_EQ(cube.density, 1000.0);
    EXPECT_EQ(cube.friction, 0.2);
    EXPECT_EQ(cube.restitution, 0.0);
    EXPECT_TRUE(cube.orientation.coeffs().isApprox(Quat::Identity().coeffs(), 0.0));
  }
  const BodySpec& floor = scene.bodies.back();
  EXPECT_EQ(floor.motion, Motion::Static);
  EXPECT_EQ(HalfExtents(floor), Vec3(50, 1, 50));
  EXPECT_EQ(floor.position, Vec3(0, -1, 0));
  EXPECT_EQ(floor.friction, 0.2);
  EXPECT_EQ(scene.world.timeStep, 1.0 / 60.0);
  EXPECT_EQ(scene.world.gravity, Vec3(0, -9.81, 0));
  EXPECT_EQ(scene.world.iterations, 0);
  EXPECT_EQ(scene.world.frictionCombine, CombineRule::Sqrt);
  EXPECT_EQ(scene.world.restitutionCombine, CombineRule::Max);
}

TEST(PyramidScene, LayersHoldTheSpecifiedCubesInOrder) {
  // Spot checks written from the definition by hand, H = 15:
  // layer 0: j, k in [0, 15) at x = -15 + 2j, y = 1;
  // layer 1: j, k in [0, 14) at x = -14 + 2j, y = 3.5;
  // layer 2: j, k in [1, 14) at x = -15 + 2j, y = 6;
  // layer 14: j = k = 7 only, at (-1, 36, -1).
  const Scenario& scene = Pyramid15();
  EXPECT_EQ(scene.bodies[0].position, Vec3(-15, 1, -15));
  EXPECT_EQ(scene.bodies[1].position, Vec3(-15, 1, -13));
  EXPECT_EQ(scene.bodies[14].position, Vec3(-15, 1, 13));
  EXPECT_EQ(scene.bodies[15].position, Vec3(-13, 1, -15));
  EXPECT_EQ(scene.bodies[224].position, Vec3(13, 1, 13));
  EXPECT_EQ(scene.bodies[225].position, Vec3(-14, 3.5, -14));
  EXPECT_EQ(scene.bodies[225 + 195].position, Vec3(12, 3.5, 12));
  EXPECT_EQ(scene.bodies[225 + 196].position, Vec3(-13, 6, -13));
  EXPECT_EQ(scene.bodies[1239].position, Vec3(-1, 36, -1));
  EXPECT_EQ(scene.bodies[1239].name, "cube_14_7_7");
}

TEST(PyramidScene, LayerSizesAreSquaresAndEveryUpperCubeSitsOnFourBelow) {
  for (int height : {1, 2, 5, 8}) {
    const Scenario scene = MakePyramidScene(height).Value();
    std::set<std::array<double, 3>> centres;
    for (const BodySpec& body : scene.bodies) {
      if (body.motion == Motion::Dynamic)
        centres.insert({body.position.x(), body.position.y(), body.position.z()});
    }
    ASSERT_EQ(static_cast<int>(centres.size()), PyramidCubeCount(height)) << "duplicate cube centres";
    for (int i = 0; i < height; ++i) {
      int inLayer = 0;
      for (const auto& c : centres) inLayer += c[1] == 1.0 + 2.5 * i ? 1 : 0;
      EXPECT_EQ(inLayer, (height - i) * (height - i)) << "H " << height << " layer " << i;
    }
    for (const auto& c : centres) {
      if (c[1] == 1.0) continue;
      for (double dx : {-1.0, 1.0}) {
        for (double dz : {-1.0, 1.0}) {
          EXPECT_TRUE(centres.count({c[0] + dx, c[1] - 2.5, c[2] + dz}))
              << "H " << height << ": cube at (" << c[0] << ", " << c[1] << ", " << c[2] << ") lacks support";
        }
      }
    }
  }
}

TEST(HullPileScene, BodyZeroFirstPointIsTheCheckValue) {
  const Scenario scene = MakeHullPileScene(10).Value();
  const Vec3& first = std::get<HullShape>(scene.bodies[0].shape).points[0];
  EXPECT_EQ(first.x(), -0.4649263239206489);
  EXPECT_EQ(first.y(), -0.3778115380165621);
  EXPECT_EQ(first.z(), 0.1980861965618116);
}

TEST(HullPileScene, PointsAreTheStreamInBodyOrderAndFramesSitOnTheLattice) {
  const int side = 3;
  const Scenario scene = MakeHullPileScene(side).Value();
  ASSERT_EQ(scene.bodies.size(), 10u * side * side + 5);
  SplitMix64 random(20261122);
  for (int j = 0; j < 10; ++j) {
    for (int k = 0; k < side; ++k) {
      for (int i = 0; i < side; ++i) {
        const int b = (j * side + k) * side + i;
        const BodySpec& body = scene.bodies[static_cast<size_t>(b)];
        ASSERT_EQ(body.motion, Motion::Dynamic);
        EXPECT_EQ(body.name, "hull_" + std::to_string(b));
        // Lattice: (1.5 (i - 1), 2 + 1.5 j, 1.5 (k - 1)) for L = 3.
        EXPECT_EQ(body.position, Vec3(1.5 * (i - 1), 2.0 + 1.5 * j, 1.5 * (k - 1))) << b;
        EXPECT_EQ(body.density, 1000.0);
        EXPECT_EQ(body.friction, 0.5);
        EXPECT_EQ(body.restitution, 0.0);
        const auto& points = std::get<HullShape>(body.shape).points;
        ASSERT_EQ(points.size(), 16u);
        for (const Vec3& point : points) {
          for (int axis = 0; axis < 3; ++axis) {
            EXPECT_EQ(point[axis], random.NextUniform() - 0.5) << "body " << b;
            EXPECT_GE(point[axis], -0.5);
            EXPECT_LT(point[axis], 0.5);
          }
        }
      }
    }
  }
}

TEST(HullPileScene, FloorAndWallsAsSpecified) {
  // L = 10: w = 0.75 * 10 + 2 = 9.5.
  const Scenario scene = MakeHullPileScene(10).Value();
  ASSERT_EQ(scene.bodies.size(), 1005u);
  EXPECT_EQ(HullPileWallInnerHalfWidth(10), 9.5);
  const auto at = [&](int index) -> const BodySpec& {
    return scene.bodies[1000 + static_cast<size_t>(index)];
  };
  for (int index = 0; index < 5; ++index) {
    EXPECT_EQ(at(index).motion, Motion::Static);
    EXPECT_EQ(at(index).friction, 0.5);
    EXPECT_EQ(at(index).restitution, 0.0);
  }
  EXPECT_EQ(HalfExtents(at(0)), Vec3(50, 1, 50));
  EXPECT_EQ(at(0).position, Vec3(0, -1, 0));
  EXPECT_EQ(HalfExtents(at(1)), Vec3(0.5, 5, 10.5));
  EXPECT_EQ(at(1).position, Vec3(10, 5, 0));
  EXPECT_EQ(HalfExtents(at(2)), Vec3(0.5, 5, 10.5));
  EXPECT_EQ(at(2).position, Vec3(-10, 5, 0));
  EXPECT_EQ(HalfExtents(at(3)), Vec3(10.5, 5, 0.5));
  EXPECT_EQ(at(3).position, Vec3(0, 5, 10));
  EXPECT_EQ(HalfExtents(at(4)), Vec3(10.5, 5, 0.5));
  EXPECT_EQ(at(4).position, Vec3(0, 5, -10));
}

TEST(BenchScenes, OutOfRangeParametersAreErrorsNamingThem) {
  const auto pyramid = MakePyramidScene(0);
  ASSERT_FALSE(pyramid.Ok());
  EXPECT_NE(pyramid.GetError().message.find("H = 0"), std::string::npos) << pyramid.GetError().message;
  const auto pile = MakeHullPileScene(101);
  ASSERT_FALSE(pile.Ok());
  EXPECT_NE(pile.GetError().message.find("L = 101"), std::string::npos) << pile.GetError().message;
  EXPECT_FALSE(MakeHullPileScene(-3).Ok());
}

TEST(BenchScenes, ListHoldsBothScenesWithTheirSeries) {
  ASSERT_EQ(BenchScenes().size(), 2u);
  const BenchScene* pyramid = FindBenchScene("pyramid");
  const BenchScene* pile = FindBenchScene("hull_pile");
  ASSERT_NE(pyramid, nullptr);
  ASSERT_NE(pile, nullptr);
  EXPECT_EQ(FindBenchScene("tower"), nullptr);
  EXPECT_EQ(pyramid->defaultParameter, 15);
  EXPECT_EQ(pile->defaultParameter, 10);
  EXPECT_EQ(pyramid->series, (std::vector<int>{10, 15, 20, 30}));
  EXPECT_EQ(pile->series, (std::vector<int>{10, 20, 40}));
  EXPECT_EQ(pile->make(4).Value().bodies.size(), 165u);
}

// Every backend must put the scene's body frame on the lattice point and
// the centre of mass at frame + centroid, whatever frame it keeps inside,
// so every hull point lands where the scene says.
TEST(HullPileScene, EveryBackendPlacesFramesAndCentresOfMassAsSpecified) {
  BackendRegistry registry;
  reference::RegisterTalusBackends(registry);
  reference::RegisterBulletBackends(registry);
  reference::RegisterOdeBackends(registry);
  const Scenario scene = MakeHullPileScene(2).Value();
  harness::Run run;
  run.id = scene.name;
  run.scenario = scene;
  run.timeStep = scene.world.timeStep;
  run.steps = 1;
  for (const char* engine : {"talus", "bullet", "ode-quickstep"}) {
    auto backend = registry.Create(engine, run);
    ASSERT_TRUE(backend.Ok()) << engine << ": " << backend.GetError().message;
    for (int b = 0; b < 40; ++b) {
      const BodySpec& body = scene.bodies[static_cast<size_t>(b)];
      const Vec3 centroid = reference::ComputeBodyMass(body).Value().centroid;
      const BodyReading state = backend.Value()->GetBodyState(b);
      // 1e-12 m: a few roundings of coordinates of size ~10 m (the frame
      // round trip through the principal axes rotation).
      EXPECT_LT((state.origin - body.position).norm(), 1e-12) << engine << " body " << b;
      EXPECT_LT((state.centerOfMass - (body.position + centroid)).norm(), 1e-12) << engine << " body " << b;
      EXPECT_LT(state.orientation.angularDistance(Quat::Identity()), 1e-12) << engine << " body " << b;
      // The centroid of 16 points in [-0.5, 0.5)^3 lies in that cube too.
      EXPECT_LT(centroid.cwiseAbs().maxCoeff(), 0.5);
    }
  }
}

}  // namespace bench_scenes_test
}  // namespace talus::harness
