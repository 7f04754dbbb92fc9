// The reference benchmark scenes (`pyramid`, `hull_pile`), built as
// engine-agnostic Scenarios so every backend constructs the same world
// through the Backend interface. The definitions are those of the
// specification in docs/bench-scenes.md; this file is the single scene list that the tests (tests/scenes),
// the `talus-scenes` program (apps/scenes) and the reports all read.
//
// Body order (an invariant the tests and the figures rely on): the dynamic
// bodies come first, in the order the scene defines them (pyramid: layer,
// then j, then k; hull_pile: body index b), so scenario body index == the
// scene's own body number; the static floor and walls follow. Every scene
// uses SI units, y up, gravity (0, -9.81, 0), time step 1/60 s, the engine's
// default solver iterations, friction combined by sqrt(f1 f2) and
// restitution by max(r1, r2). Sleeping is a backend setting, never a scene
// field: every backend registered with the harness keeps bodies awake.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "talus/harness/scenario/scenario.h"
#include "talus/result.h"

namespace talus::harness {

/// Time step of every reference scene, seconds.
inline constexpr double kBenchTimeStep = 1.0 / 60.0;
/// Steps a reference run takes unless told otherwise (10 s of simulated time).
inline constexpr int kBenchDefaultSteps = 600;
/// Density of every dynamic body, kg/m^3 (water).
inline constexpr double kBenchDensity = 1000.0;

/// Pyramid: cube half extent (m) and the friction of cubes and floor.
inline constexpr double kPyramidCubeHalfExtent = 1.0;
inline constexpr double kPyramidFriction = 0.2;
/// Pyramid: vertical pitch between layer centres, metres (cubes are 2 m tall,
/// so each layer starts 0.5 m above the one below and drops onto it).
inline constexpr double kPyramidLayerPitch = 2.5;
/// Pyramid: valid range of the height parameter H (layers). H = 100 is
/// already 338,350 cubes.
inline constexpr int kPyramidMinHeight = 1;
inline constexpr int kPyramidMaxHeight = 100;

/// Hull pile: seed of the one SplitMix64 stream that draws every point.
inline constexpr std::uint64_t kHullPileSeed = 20261122;
/// Hull pile: layers of bodies (j = 0 .. kHullPileLayers - 1).
inline constexpr int kHullPileLayers = 10;
/// Hull pile: random points drawn per body (each 3 uniforms x, y, z).
inline constexpr int kHullPilePointsPerBody = 16;
/// Hull pile: lattice spacing of the body frames, metres.
inline constexpr double kHullPileSpacing = 1.5;
/// Hull pile: friction of every body, walls and floor included.
inline constexpr double kHullPileFriction = 0.5;
/// Hull pile: valid range of the side parameter L (N = 10 L^2 bodies).
inline constexpr int kHullPileMinSide = 1;
inline constexpr int kHullPileMaxSide = 100;

/// Half extents (50, 1, 50) and centre (0, -1, 0) of the static floor of
/// both scenes: its top face is the plane y = 0.
inline const Vec3 kBenchFloorHalfExtents{50.0, 1.0, 50.0};
inline const Vec3 kBenchFloorCenter{0.0, -1.0, 0.0};

/// The `pyramid` scene of height H (layers, in [kPyramidMinHeight,
/// kPyramidMaxHeight]; H = 15 gives 1240 cubes): layer i = 0..H-1 holds the
/// cubes with integer j, k in [floor(i/2), H - floor((i+1)/2)) at
/// x = -H + 2j + (i odd), y = 1 + 2.5 i, z = -H + 2k + (i odd), on a static
/// floor box. An H out of range is an Error naming it.
Result<Scenario> MakePyramidScene(int height);

/// Number of cubes of a pyramid of height H: sum over layers of (H - i)^2.
int PyramidCubeCount(int height);

/// The `hull_pile` scene of side L (in [kHullPileMinSide,
/// kHullPileMaxSide]; N = 10 L^2 hulls): body b = (j L + k) L + i is the
/// hull of 16 SplitMix64 points in [-0.5, 0.5)^3 of its own frame, whose
/// origin sits at (1.5 (i - (L-1)/2), 2 + 1.5 j, 1.5 (k - (L-1)/2)); a floor
/// and four walls of inner half width HullPileWallInnerHalfWidth(L) hold
/// them. An L out of range is an Error naming it.
Result<Scenario> MakeHullPileScene(int side);

/// w = 0.75 L + 2: the inner faces of the hull pile's walls are the planes
/// x = +-w and z = +-w (metres).
double HullPileWallInnerHalfWidth(int side);

/// The scene's identity: which figures it reports.
enum class BenchSceneKind { Pyramid, HullPile };

/// One entry of the scene list.
struct BenchScene {
  BenchSceneKind kind;
  std::string_view name;           ///< "pyramid", "hull_pile": the --scene value
  std::string_view parameterName;  ///< "H", "L"
  int defaultParameter;            ///< 15, 10
  int minParameter;                ///< smallest valid parameter
  int maxParameter;                ///< largest valid parameter
  std::vector<int> series;         ///< the scaling series, ascending
  Result<Scenario> (*make)(int);   ///< builds the scene for a parameter
};

/// Every reference scene, in a fixed order (pyramid, hull_pile).
const std::vector<BenchScene>& BenchScenes();

/// The scene called `name`, or nullptr.
const BenchScene* FindBenchScene(std::string_view name);

}  // namespace talus::harness
