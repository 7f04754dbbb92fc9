// The soft step (MethodSettings::stepSolver = SoftStep, dynamics/
// soft_step_solver.h) through the whole pipeline: its settings refused when
// invalid, the soft row against the implicit Euler spring it stands for,
// rest heights against the springs' static deflection, a sliding stop
// against v0^2 / (2 mu g), heavy boxes on light ones, and the same bits for
// any thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "dynamics/soft_contact_rows.h"
#include "talus/world.h"

namespace talus {
namespace soft_step_test {

constexpr double kH = 1.0 / 60.0;
constexpr double kG = 9.81;

Shape Box(const Vec3& half) { return Shape::CreateBox(half).Value(); }

WorldSettings SoftSettings() {
  WorldSettings settings;
  settings.methods.stepSolver = StepSolver::SoftStep;
  settings.sleeping = false;  // every step solves the scene
  return settings;
}

// The spring frequencies of a 1/60 s step with the default soft settings:
// 4 sub-steps are 240 Hz, a quarter of that is 60 Hz, above the 30 Hz
// cap: 30 Hz between two moving bodies, twice that against the ground.
double Omega(double hertz) { return 2.0 * std::numbers::pi * hertz; }
const double kOmegaPair = Omega(30.0);
const double kOmegaGround = Omega(60.0);

BodyId AddGround(World& world, double friction = 0.5) {
  return world
      .CreateBody({.type = BodyType::Static,
                   .position = {0, -0.5, 0},
                   .shape = Box({50, 0.5, 50}),
                   .friction = friction})
      .Value();
}

BodyId AddBox(World& world, const Vec3& position, const Vec3& half, double density, double friction = 0.5) {
  return world
      .CreateBody({.type = BodyType::Dynamic,
                   .position = position,
                   .shape = Box(half),
                   .density = density,
                   .friction = friction})
      .Value();
}

TEST(SoftStep, InvalidSettingsAreRefusedNamingTheField) {
  struct Case {
    const char* field;
    void (*spoil)(WorldSettings&);
  };
  const Case cases[] = {
      {"softStep.substeps", [](WorldSettings& s) { s.methods.softStep.substeps = 0; }},
      {"softStep.substeps", [](WorldSettings& s) { s.methods.softStep.substeps = 1001; }},
      {"softStep.contactHertz", [](WorldSettings& s) { s.methods.softStep.contactHertz = std::nan(""); }},
      {"softStep.contactHertz", [](WorldSettings& s) { s.methods.softStep.contactHertz = INFINITY; }},
      {"softStep.contactHertz", [](WorldSettings& s) { s.methods.softStep.contactHertz = 0.0; }},
      {"softStep.dampingRatio", [](WorldSettings& s) { s.methods.softStep.dampingRatio = -1.0; }},
      {"softStep.dampingRatio", [](WorldSettings& s) { s.methods.softStep.dampingRatio = std::nan(""); }},
      {"softStep.pushOutSpeed", [](WorldSettings& s) { s.methods.softStep.pushOutSpeed = 0.0; }},
      {"softStep.pushOutSpeed", [](WorldSettings& s) { s.methods.softStep.pushOutSpeed = -INFINITY; }},
      {"stepSolver", [](WorldSettings& s) { s.methods.stepSolver = static_cast<StepSolver>(7); }},
  };
  for (const Case& c : cases) {
    WorldSettings settings = SoftSettings();
    c.spoil(settings);
    const Result<World> world = World::Create(settings);
    ASSERT_FALSE(world) << c.field;
    EXPECT_NE(world.GetError().message.find(std::string("WorldSettings.methods.") + c.field),
              std::string::npos)
        << world.GetError().message;
    // The same check guards SetSettings, and a refusal changes nothing.
    World valid = World::Create(SoftSettings()).Value();
    EXPECT_FALSE(valid.SetSettings(settings));
    EXPECT_EQ(valid.Settings().methods.softStep.substeps, SoftStepSettings{}.substeps);
  }
  // Bad soft values are refused even while Sequential Impulses is selected,
  // so switching solvers later cannot meet them.
  WorldSettings settings;
  settings.methods.softStep.substeps = 0;
  EXPECT_FALSE(World::Create(settings));
}

TEST(SoftStep, SoftRowIsTheImplicitEulerSpring) {
  // The header's derivation: a row of effective mass m and error C, as a
  // spring k = m w^2 with damper c = 2 m z w stepped by implicit Euler,
  //   m (v2 - v1) = -h (k (C + h v2) + c v2),
  // must get the impulse -m massScale (v1 + biasRate C). Random cases; the
  // two are the same rational expression, so they agree to round-off
  // (1e-12 relative: a few operations on doubles of the same scale).
  std::mt19937_64 random(27);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    const double hertz = 1.0 + 100.0 * unit(random);
    const double zeta = 20.0 * unit(random);
    const double h = 1e-4 + 0.05 * unit(random);
    const double m = 0.01 + 1000.0 * unit(random);
    const double error = -0.1 + 0.2 * unit(random);
    const double v1 = -5.0 + 10.0 * unit(random);
    const double w = 2.0 * std::numbers::pi * hertz;
    const double k = m * w * w;
    const double c = 2.0 * m * zeta * w;
    const double v2 = (m * v1 - h * k * error) / (m + h * c + h * h * k);
    const double implicit = m * (v2 - v1);
    const Softness soft = MakeSoftness(hertz, zeta, h);
    const double row = -m * soft.massScale * (v1 + soft.biasRate * error);
    EXPECT_NEAR(row, implicit, 1e-12 * (std::abs(implicit) + m * std::abs(v1) + k * h * std::abs(error)));
    EXPECT_NEAR(soft.massScale + soft.impulseScale, 1.0, 1e-15);
  }
}

TEST(SoftStep, BoxRestsAtTheGroundSpringsStaticDeflection) {
  // At rest the pair's block must ask for nothing:
  //   -massScale K+ biasRate C - impulseScale lambda = 0, so
  //   C = -K lambda / (h w^2)  (massScale biasRate / impulseScale = h w^2),
  // with lambda the corners' shares of the weight over a sub-step, m g h / 4
  // each. Row i of K lambda is (m g h / 4) (4/m + (r_i x n) . I^-1 sum_j
  // (r_j x n)), and the corners' arms cancel in the sum: C = -g / w^2.
  // Against the ground, w = 2 pi 60 Hz: the box sinks 69 um. After 3 s the
  // over-damped transient (slowest rate w / (2 z) = 19/s, e^-57) is gone, so
  // the height must match to round-off of the positions (1e-9 m).
  World world = World::Create(SoftSettings()).Value();
  AddGround(world);
  const BodyId box = AddBox(world, {0, 0.5, 0}, Vec3::Constant(0.5), 1000.0);
  for (int n = 0; n < 180; ++n) ASSERT_TRUE(world.Step(kH));
  const BodyState state = world.GetBodyState(box).Value();
  const double sink = kG / (kOmegaGround * kOmegaGround);
  EXPECT_NEAR(state.position.y(), 0.5 - sink, 1e-9);
  // The block shares the load evenly, so nothing tilts it: round-off only.
  EXPECT_LT(std::hypot(state.position.x(), state.position.z()), 1e-9);
  EXPECT_LT(state.linearVelocity.norm(), 1e-9);
}

TEST(SoftStep, ColumnOfBoxesStandsAtTheSpringsDeflections) {
  // Five 1 m cubes. Contact j carries the N - j boxes above it, shared by
  // four corners; at rest C = -K lambda / (h w^2) (above), the corners'
  // arms cancel in K lambda: on the ground, K lambda = (N - j) g h and
  // w = w_g: C_0 = N g / w_g^2; between two cubes both masses count,
  // K lambda = 2 (N - j) g h at w_p: C_j = 2 (N - j) g / w_p^2. Box k sits
  // at k + 1/2 - sum_{j<=k} C_j (the top one 5.9 mm low). Tolerance
  // 1e-7 m, 0.03% of the smallest deflection checked (0.35 mm): after 6 s
  // the slowest mode of the column (its springs in series) is below it.
  constexpr int kBoxes = 5;
  World world = World::Create(SoftSettings()).Value();
  AddGround(world);
  std::vector<BodyId> boxes;
  for (int k = 0; k < kBoxes; ++k)
    boxes.push_back(AddBox(world, {0, k + 0.5, 0}, Vec3::Constant(0.5), 1000.0));
  double horizontal = 0.0;
  for (int n = 0; n < 360; ++n) {
    ASSERT_TRUE(world.Step(kH));
    for (const BodyId id : boxes) {
      const Vec3 p = world.GetBodyState(id).Value().position;
      horizontal = std::max(horizontal, std::hypot(p.x(), p.z()));
    }
  }
  double sunk = kBoxes * kG / (kOmegaGround * kOmegaGround);
  for (int k = 0; k < kBoxes; ++k) {
    if (k > 0) sunk += 2.0 * (kBoxes - k) * kG / (kOmegaPair * kOmegaPair);
    EXPECT_NEAR(world.GetBodyState(boxes[static_cast<std::size_t>(k)]).Value().position.y(), k + 0.5 - sunk,
                1e-7)
        << "box " << k;
  }
  // Standing, with no sway: a fall moves the top box by metres. In the first
  // steps a pair touches at only some corners while its speculative ones
  // close, and those are solved point by point, so the column leans a
  // little (measured 35 um at the top, 0.5 um at rest); 0.1 mm is a
  // tenth of the write-up solver's 1 mm requirement on a 10-box column.
  EXPECT_LT(horizontal, 1e-4);
}

TEST(SoftStep, SlidingBoxStopsAtTheCoulombDistance) {
  // A cube resting on the ground (mu = 0.5 on both, geometric mean 0.5) is
  // given v0 = 2 m/s along x. Friction takes mu g h off its speed each
  // sub-step (h = dt / 4) while the normal rows hold its weight, and the
  // position moves by h v after each sub-step's friction, so it stops after
  // the discrete sum h (v0 - mu g h) + h (v0 - 2 mu g h) + ...
  // = v0^2 / (2 mu g) - h v0 / 2 (+ mu g h^2 f (1 - f) / 2 <= 1.1e-5 m for
  // the fraction f of a sub-step left at the stop). Tolerance 1e-4 m,
  // 0.025% of the 0.4 m slide: besides that term, the friction's torque
  // shifts the corners' normal impulses when the slide starts, which the
  // soft rows follow over a few sub-steps (measured 3e-5 m in all).
  World world = World::Create(SoftSettings()).Value();
  AddGround(world);
  const BodyId box = AddBox(world, {0, 0.5, 0}, Vec3::Constant(0.5), 1000.0);
  for (int n = 0; n < 60; ++n) ASSERT_TRUE(world.Step(kH));
  const double x0 = world.GetBodyState(box).Value().position.x();
  const double v0 = 2.0;
  ASSERT_TRUE(world.SetLinearVelocity(box, {v0, 0, 0}));
  for (int n = 0; n < 120; ++n) ASSERT_TRUE(world.Step(kH));
  const BodyState state = world.GetBodyState(box).Value();
  const double mu = 0.5;
  const double distance = state.position.x() - x0;
  const double h = kH / SoftStepSettings{}.substeps;
  EXPECT_NEAR(distance, v0 * v0 / (2.0 * mu * kG) - 0.5 * h * v0, 1e-4);
  EXPECT_LT(state.linearVelocity.norm(), 1e-6);  // stopped, not creeping
  // Straight, within the per-point friction's yaw: each point's friction
  // row turns the box before the next point's is solved (as
  // FrictionSolve::PerPoint in Sequential Impulses), so the t2 rows see a
  // little sideways slip. Measured 4.4e-5 m sideways; 4e-4 m (0.1% of the
  // slide) keeps it a side effect.
  EXPECT_LT(std::abs(state.position.z()), 4e-4);
}

// Mechanical energy of the dynamic bodies: kinetic (linear and angular)
// plus potential m g y of the centre of mass, J.
double Energy(const World& world, const std::vector<BodyId>& bodies) {
  double energy = 0.0;
  for (const BodyId id : bodies) {
    const BodyState s = world.GetBodyState(id).Value();
    const Mat3 r = s.orientation.toRotationMatrix();
    const Mat3 inertia = r * s.localInertia * r.transpose();
    energy += 0.5 * s.mass * s.linearVelocity.squaredNorm() +
              0.5 * s.angularVelocity.dot(inertia * s.angularVelocity) + s.mass * kG * s.centerOfMass.y();
  }
  return energy;
}

// A heavy plank (3 x 0.5 x 1 m) resting on two 0.5 m cubes `ratio` times
// lighter, placed exactly touching, stepped 5 s.
void CheckHeavyOnLight(double ratio) {
  constexpr double kSupportHalf = 0.25;
  constexpr double kSupportDensity = 1000.0;
  const Vec3 plankHalf(1.5, 0.25, 0.5);
  const double m = kSupportDensity * 8.0 * kSupportHalf * kSupportHalf * kSupportHalf;
  const double plankVolume = 8.0 * plankHalf.prod();
  const double bigM = ratio * m;
  World world = World::Create(SoftSettings()).Value();
  AddGround(world);
  const double supportX = 1.0;
  std::vector<BodyId> bodies;
  bodies.push_back(
      AddBox(world, {-supportX, kSupportHalf, 0}, Vec3::Constant(kSupportHalf), kSupportDensity));
  bodies.push_back(AddBox(world, {supportX, kSupportHalf, 0}, Vec3::Constant(kSupportHalf), kSupportDensity));
  const double plankY = 2.0 * kSupportHalf + plankHalf.y();
  bodies.push_back(AddBox(world, {0, plankY, 0}, plankHalf, bigM / plankVolume));
  std::vector<double> startHeight;
  for (const BodyId id : bodies) startHeight.push_back(world.GetBodyState(id).Value().centerOfMass.y());
  const double startEnergy = Energy(world, bodies);
  double rise = 0.0;
  double gain = 0.0;
  for (int n = 0; n < 300; ++n) {
    ASSERT_TRUE(world.Step(kH));
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      rise = std::max(rise, world.GetBodyState(bodies[i]).Value().centerOfMass.y() - startHeight[i]);
    }
    gain = std::max(gain, Energy(world, bodies) - startEnergy);
  }
  // Nothing gains height and the energy never grows: the springs are
  // over-damped (z = 10) and only ever push out an overlap they measured,
  // so the bodies sink into place. Tolerances: round-off of the heights
  // (1e-9 m) and of the energy sum (1e-9 of the plank's m g y).
  EXPECT_LT(rise, 1e-9) << "ratio " << ratio;
  EXPECT_LT(gain, 1e-9 * bigM * kG * plankY) << "ratio " << ratio;

  // How far the plank sank, against the springs' deflections at rest
  // (C = -K lambda / (h w^2), BoxRestsAtTheGroundSpringsStaticDeflection),
  // averaged over a pair's four corners. Ground: each support's corners
  // carry (M/2 + m) g; their arms about the support's centre cancel, so
  // the mean sink is (M / (2m) + 1) g / w_g^2. Top: each support's corners
  // carry M g / 2; the support's arms cancel again, the plank's do not
  // (its arm to the support's centre is d = 1 m along x): the mean sink
  // is (M g / 2)(1/m + 1/M + d^2 / I_z) / w_p^2, I_z the plank's inertia
  // about z. The plank, level by symmetry, sinks by the sum. Tolerance:
  // where the support's load centre sits off its middle by e (at most its
  // half width) the plank's term moves by d e / I_z against 1/m, 4e-5 of
  // it at 1000:1; and the transient left after 5 s (below 1e-5 m
  // measured). 1e-4 of the sink covers both.
  const double plankIz = bigM * (plankHalf.x() * plankHalf.x() + plankHalf.y() * plankHalf.y()) / 3.0;
  const double ground = (bigM / (2.0 * m) + 1.0) * kG / (kOmegaGround * kOmegaGround);
  const double top =
      0.5 * bigM * kG * (1.0 / m + 1.0 / bigM + supportX * supportX / plankIz) / (kOmegaPair * kOmegaPair);
  const double sank = plankY - world.GetBodyState(bodies[2]).Value().centerOfMass.y();
  // Not crushed: never deeper than the springs' deflection at rest.
  EXPECT_LE(sank, (1.0 + 1e-4) * (ground + top)) << "ratio " << ratio;
  // The deflection itself, where the model's upright supports hold: at
  // 100:1. At 1000:1 the supports, 13 cm into the plank's springs, settle
  // turned (measured 0.018 rad about the vertical, 2e-3 rad tilt) since
  // every clipped contact point is kept inside both shapes, and the plank
  // sinks 0.11 mm (6.6e-4) less than the upright model says; that model
  // does not describe turned supports, so only the bound above is asserted
  // there (docs/dynamics.md, "The soft step").
  if (ratio <= 100.0) {
    EXPECT_NEAR(sank, ground + top, 1e-4 * (ground + top)) << "ratio " << ratio;
  }
}

TEST(SoftStep, HeavyPlankOnLightCubesAt100To1) { CheckHeavyOnLight(100.0); }
TEST(SoftStep, HeavyPlankOnLightCubesAt1000To1) { CheckHeavyOnLight(1000.0); }

// A pile of boxes dropped at odd angles, `threads` threads: the final
// states as raw bytes.
std::vector<unsigned char> PileBytes(int threads) {
  WorldSettings settings = SoftSettings();
  settings.threads = threads;
  World world = World::Create(settings).Value();
  AddGround(world);
  std::vector<BodyId> boxes;
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> angle(-0.4, 0.4);
  for (int layer = 0; layer < 6; ++layer) {
    for (int i = 0; i < 6; ++i) {
      for (int k = 0; k < 6; ++k) {
        const Quat q = Quat(Eigen::AngleAxisd(angle(random), Vec3::UnitX())) *
                       Quat(Eigen::AngleAxisd(angle(random), Vec3::UnitZ()));
        boxes.push_back(world
                            .CreateBody({.type = BodyType::Dynamic,
                                         .position = {i * 1.1 - 3.0, 0.6 + 1.1 * layer, k * 1.1 - 3.0},
                                         .orientation = q,
                                         .shape = Box(Vec3::Constant(0.45)),
                                         .density = 1000.0,
                                         .friction = 0.6})
                            .Value());
      }
    }
  }
  StepStatistics last;
  for (int n = 0; n < 150; ++n) {
    const Result<StepStatistics> stats = world.Step(kH);
    EXPECT_TRUE(stats);
    if (stats) last = stats.Value();
  }
  // The pile must exercise the cut: several colours, and more pairs than
  // one chunk of a colour (16) holds.
  EXPECT_GT(last.solverColours, 1);
  EXPECT_GT(last.manifolds, 4 * 16);
  std::vector<unsigned char> bytes;
  for (const BodyId id : boxes) {
    const BodyState s = world.GetBodyState(id).Value();
    for (const double value :
         {s.position.x(), s.position.y(), s.position.z(), s.orientation.w(), s.orientation.x(),
          s.orientation.y(), s.orientation.z(), s.linearVelocity.x(), s.linearVelocity.y(),
          s.linearVelocity.z(), s.angularVelocity.x(), s.angularVelocity.y(), s.angularVelocity.z()}) {
      unsigned char raw[sizeof(double)];
      std::memcpy(raw, &value, sizeof(double));
      bytes.insert(bytes.end(), raw, raw + sizeof(double));
    }
  }
  return bytes;
}

TEST(SoftStep, BitIdenticalForAnyThreadCount) {
  // 216 boxes landing in a heap: hundreds of pairs over many colours, so a
  // colour's pairs are cut into several chunks that threads share.
  const std::vector<unsigned char> one = PileBytes(1);
  EXPECT_EQ(PileBytes(2), one);
  EXPECT_EQ(PileBytes(3), one);
}

}  // namespace soft_step_test
}  // namespace talus
