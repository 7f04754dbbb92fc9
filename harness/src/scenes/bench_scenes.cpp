// The reference benchmark scenes (see talus/harness/scenes/bench_scenes.h and
// docs/bench-scenes.md). Each builder is a direct transcription of the
// scene's specification there: the layout loops run in the order the
// definition numbers the bodies, so body numbers, random draws and scenario
// indices agree.
#include "talus/harness/scenes/bench_scenes.h"

#include <string>

#include "talus/harness/support/split_mix64.h"

namespace talus::harness {
namespace {

// The settings every reference scene shares: 1/60 s steps, engine-default
// iterations, sqrt friction, max restitution.
Scenario MakeEmptyScene(std::string name, std::string description) {
  Scenario scene;
  scene.name = std::move(name);
  scene.description = std::move(description);
  scene.world.gravity = Vec3(0.0, -9.81, 0.0);
  scene.world.timeStep = kBenchTimeStep;
  scene.world.iterations = 0;
  scene.world.steps = kBenchDefaultSteps;
  scene.world.frictionCombine = CombineRule::Sqrt;
  scene.world.restitutionCombine = CombineRule::Max;
  scene.measure = {Quantity::Position, Quantity::Velocity, Quantity::Energy, Quantity::Contacts,
                   Quantity::Penetration};
  return scene;
}

BodySpec MakeStaticBox(std::string name, const Vec3& halfExtents, const Vec3& center, double friction) {
  BodySpec box;
  box.name = std::move(name);
  box.shape = BoxShape{halfExtents};
  box.motion = Motion::Static;
  box.position = center;
  box.friction = friction;
  box.restitution = 0.0;
  return box;
}

}  // namespace

int PyramidCubeCount(int height) {
  int count = 0;
  for (int i = 0; i < height; ++i) count += (height - i) * (height - i);
  return count;
}

Result<Scenario> MakePyramidScene(int height) {
  if (height < kPyramidMinHeight || height > kPyramidMaxHeight) {
    return Error{"pyramid: height H = " + std::to_string(height) + " is out of range [" +
                 std::to_string(kPyramidMinHeight) + ", " + std::to_string(kPyramidMaxHeight) + "]"};
  }
  Scenario scene = MakeEmptyScene("pyramid[H=" + std::to_string(height) + "]",
                                  "square-layered pyramid of 2 m cubes, Jolt's performance-test layout");
  scene.bodies.reserve(static_cast<size_t>(PyramidCubeCount(height)) + 1);
  const double h = static_cast<double>(height);
  for (int i = 0; i < height; ++i) {
    // Layer i spans [floor(i/2), H - floor((i+1)/2)) in j and k; odd layers
    // shift by one cube half so each cube rests on four below it.
    const int first = i / 2;
    const int end = height - (i + 1) / 2;
    const double shift = (i % 2 == 1) ? 1.0 : 0.0;
    for (int j = first; j < end; ++j) {
      for (int k = first; k < end; ++k) {
        BodySpec cube;
        cube.name = "cube_" + std::to_string(i) + "_" + std::to_string(j) + "_" + std::to_string(k);
        cube.shape = BoxShape{Vec3::Constant(kPyramidCubeHalfExtent)};
        cube.motion = Motion::Dynamic;
        cube.position = Vec3(-h + 2.0 * j + shift, 1.0 + kPyramidLayerPitch * i, -h + 2.0 * k + shift);
        cube.density = kBenchDensity;
        cube.friction = kPyramidFriction;
        cube.restitution = 0.0;
        scene.bodies.push_back(std::move(cube));
      }
    }
  }
  scene.bodies.push_back(MakeStaticBox("floor", kBenchFloorHalfExtents, kBenchFloorCenter, kPyramidFriction));
  return scene;
}

double HullPileWallInnerHalfWidth(int side) { return 0.75 * side + 2.0; }

Result<Scenario> MakeHullPileScene(int side) {
  if (side < kHullPileMinSide || side > kHullPileMaxSide) {
    return Error{"hull_pile: side L = " + std::to_string(side) + " is out of range [" +
                 std::to_string(kHullPileMinSide) + ", " + std::to_string(kHullPileMaxSide) + "]"};
  }
  Scenario scene = MakeEmptyScene("hull_pile[L=" + std::to_string(side) + "]",
                                  "10 L^2 random convex hulls poured into a walled box");
  const int count = kHullPileLayers * side * side;
  scene.bodies.reserve(static_cast<size_t>(count) + 5);
  // One stream for the whole scene, drawn in increasing body number b,
  // 16 points per body, x then y then z per point.
  SplitMix64 random(kHullPileSeed);
  const double center = 0.5 * (side - 1);
  for (int j = 0; j < kHullPileLayers; ++j) {
    for (int k = 0; k < side; ++k) {
      for (int i = 0; i < side; ++i) {
        const int b = (j * side + k) * side + i;
        HullShape hull;
        hull.points.reserve(kHullPilePointsPerBody);
        for (int p = 0; p < kHullPilePointsPerBody; ++p) {
          const double x = random.NextUniform() - 0.5;
          const double y = random.NextUniform() - 0.5;
          const double z = random.NextUniform() - 0.5;
          hull.points.emplace_back(x, y, z);
        }
        BodySpec body;
        body.name = "hull_" + std::to_string(b);
        body.shape = std::move(hull);
        body.motion = Motion::Dynamic;
        body.position = Vec3(kHullPileSpacing * (i - center), 2.0 + kHullPileSpacing * j,
                             kHullPileSpacing * (k - center));
        body.density = kBenchDensity;
        body.friction = kHullPileFriction;
        body.restitution = 0.0;
        scene.bodies.push_back(std::move(body));
      }
    }
  }
  scene.bodies.push_back(
      MakeStaticBox("floor", kBenchFloorHalfExtents, kBenchFloorCenter, kHullPileFriction));
  // Walls 1 m thick and 10 m tall whose inner faces are x = +-w and z = +-w;
  // the x walls are 2 (w + 1) long so they close the corners.
  const double w = HullPileWallInnerHalfWidth(side);
  const Vec3 xWall(0.5, 5.0, w + 1.0);
  const Vec3 zWall(w + 1.0, 5.0, 0.5);
  scene.bodies.push_back(MakeStaticBox("wall_+x", xWall, Vec3(w + 0.5, 5.0, 0.0), kHullPileFriction));
  scene.bodies.push_back(MakeStaticBox("wall_-x", xWall, Vec3(-(w + 0.5), 5.0, 0.0), kHullPileFriction));
  scene.bodies.push_back(MakeStaticBox("wall_+z", zWall, Vec3(0.0, 5.0, w + 0.5), kHullPileFriction));
  scene.bodies.push_back(MakeStaticBox("wall_-z", zWall, Vec3(0.0, 5.0, -(w + 0.5)), kHullPileFriction));
  return scene;
}

const std::vector<BenchScene>& BenchScenes() {
  static const std::vector<BenchScene> scenes = {
      {BenchSceneKind::Pyramid,
       "pyramid",
       "H",
       15,
       kPyramidMinHeight,
       kPyramidMaxHeight,
       {10, 15, 20, 30},
       &MakePyramidScene},
      {BenchSceneKind::HullPile,
       "hull_pile",
       "L",
       10,
       kHullPileMinSide,
       kHullPileMaxSide,
       {10, 20, 40},
       &MakeHullPileScene},
  };
  return scenes;
}

const BenchScene* FindBenchScene(std::string_view name) {
  for (const BenchScene& scene : BenchScenes()) {
    if (scene.name == name) return &scene;
  }
  return nullptr;
}

}  // namespace talus::harness
