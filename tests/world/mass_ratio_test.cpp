// Heavy loads on light supports under the engine's defaults
// (MethodSettings::shockPropagation, docs/dynamics.md "Shock propagation").
// Judged by what rigid contact allows, not by the solver's own numbers:
// bodies placed touching may sink into their contacts by at most the slop
// each (position correction leaves that band alone), may not rise above
// where they started (no contact pulls or pushes a resting body up), and
// the total energy may not grow.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "talus/world.h"

namespace talus {
namespace mass_ratio_test {

constexpr double kH = 1.0 / 60.0;
constexpr double kG = 9.81;

struct Extremes {
  std::array<double, 3> highest{};  ///< largest rise of each body above its start, m
  std::array<double, 3> lowest{};   ///< largest sink below its start, m
  double energyRise = 0.0;          ///< largest E(t) - E(0), J
};

// A slab (3 x 0.5 x 1 m) of `ratio` kg resting on two 0.5 m cubes of 1 kg
// near its ends, on a static ground, all placed touching; 5 s at 60 Hz with
// the default 10 sweeps.
Extremes SlabOnTwoBoxes(double ratio, const WorldSettings& settings) {
  World world = World::Create(settings).Value();
  EXPECT_TRUE(world.CreateBody({.type = BodyType::Static,
                                .position = {0, -0.5, 0},
                                .shape = Shape::CreateBox({10, 0.5, 10}).Value()}));
  const std::array<Vec3, 3> starts = {Vec3(-1.25, 0.25, 0), Vec3(1.25, 0.25, 0), Vec3(0, 0.75, 0)};
  std::array<BodyId, 3> ids{};
  for (int i = 0; i < 3; ++i) {
    const bool slab = i == 2;
    ids[static_cast<std::size_t>(i)] =
        world
            .CreateBody(
                {.type = BodyType::Dynamic,
                 .position = starts[static_cast<std::size_t>(i)],
                 .shape = Shape::CreateBox(slab ? Vec3(1.5, 0.25, 0.5) : Vec3(0.25, 0.25, 0.25)).Value(),
                 .density = slab ? ratio / 1.5 : 8.0})
            .Value();
  }
  const auto energy = [&] {
    double e = 0.0;
    for (const BodyId id : ids) {
      const BodyState s = world.GetBodyState(id).Value();
      e += s.mass * (0.5 * s.linearVelocity.squaredNorm() + kG * s.centerOfMass.y()) +
           0.5 * s.angularVelocity.dot(s.orientation.toRotationMatrix() * s.localInertia *
                                       s.orientation.toRotationMatrix().transpose() * s.angularVelocity);
    }
    return e;
  };
  const double e0 = energy();
  Extremes out;
  for (int n = 0; n < 300; ++n) {
    EXPECT_TRUE(world.Step(kH));
    for (std::size_t i = 0; i < 3; ++i) {
      const double dy = world.GetBodyState(ids[i]).Value().centerOfMass.y() - starts[i].y();
      out.highest[i] = std::max(out.highest[i], dy);
      out.lowest[i] = std::min(out.lowest[i], dy);
    }
    out.energyRise = std::max(out.energyRise, energy() - e0);
  }
  return out;
}

WorldSettings Defaults() { return WorldSettings{.gravity = {0.0, -kG, 0.0}}; }

TEST(MassRatio, ASlabUpToAThousandTimesItsSupportsRestsOnThem) {
  for (const double ratio : {10.0, 100.0, 400.0, 1000.0}) {
    SCOPED_TRACE(ratio);
    const Extremes e = SlabOnTwoBoxes(ratio, Defaults());
    const double slop = Defaults().slop;
    for (std::size_t i = 0; i < 3; ++i) {
      // Rise: 0.1 mm, a fortieth of the slop: rigid supports cannot lift a
      // body placed touching them; what is allowed is the solver's residual,
      // far below the metres an unconverged solve throws the slab.
      EXPECT_LT(e.highest[i], 1e-4) << "body " << i;
      // Sink: one slop per contact below the body (cubes one, slab two).
      EXPECT_GT(e.lowest[i], -(i == 2 ? 2.0 : 1.0) * slop) << "body " << i;
    }
    // Energy: at most what lifting the slab by the same 0.1 mm costs.
    EXPECT_LT(e.energyRise, ratio * kG * 1e-4);
  }
}

TEST(MassRatio, WithoutShockPropagationTheThousandToOneSlabIsThrown) {
  // The same check fails the sweeps alone: what the default is for.
  WorldSettings settings = Defaults();
  settings.methods.shockPropagation = false;
  const Extremes e = SlabOnTwoBoxes(1000.0, settings);
  const double rise = *std::max_element(e.highest.begin(), e.highest.end());
  EXPECT_GT(std::max(rise, e.energyRise / (1000.0 * kG)), 1e-4);
}

}  // namespace mass_ratio_test
}  // namespace talus
