// The coloured wide contact solver (ContactOrder::ByColour): the
// colouring's invariant, the wide lanes against the scalar reference where
// the two must agree bit for bit (pairs that share no movable body), any cut
// of a colour into ranges (and threads) giving bit-identical states, and
// the overflow colour.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <random>
#include <set>
#include <thread>
#include <vector>

#include "contact_scene.h"
#include "dynamics/constraint_colouring.h"

namespace talus {
namespace coloured_solver_test {

using testing::ContactScene;
using testing::GroundPlane;

constexpr double kH = 1.0 / 60.0;

// FNV-1a over the bits of every body's pose and velocities.
std::uint64_t HashState(std::span<const BodySim> bodies) {
  std::uint64_t hash = 1469598103934665603ull;
  const auto add = [&hash](const double* values, int count) {
    for (int i = 0; i < count; ++i) {
      std::uint64_t bits = 0;
      std::memcpy(&bits, &values[i], sizeof bits);
      for (int b = 0; b < 8; ++b) {
        hash ^= (bits >> (8 * b)) & 0xFFu;
        hash *= 1099511628211ull;
      }
    }
  };
  for (const BodySim& body : bodies) {
    add(body.center.data(), 3);
    add(body.orientation.coeffs().data(), 4);
    add(body.linearVelocity.data(), 3);
    add(body.angularVelocity.data(), 3);
  }
  return hash;
}

TEST(ConstraintColouring, NoColourHasTwoPairsOnOneMovableBodyAndTheResultRepeats) {
  // Random graphs: 60 bodies, the first 5 immovable (shared freely), 300
  // pairs. Property: within a colour, no movable body appears twice; an
  // overflow pair had every colour taken by its bodies; same input, same
  // colours.
  std::mt19937 random(7);
  for (int trial = 0; trial < 50; ++trial) {
    constexpr int kBodies = 60;
    std::uniform_int_distribution<int> body(0, kBodies - 1);
    std::vector<ColourInput> pairs;
    for (int i = 0; i < 300; ++i) {
      int a = body(random);
      int b = body(random);
      while (b == a) b = body(random);
      pairs.push_back({.bodyA = a, .bodyB = b, .movesA = a >= 5, .movesB = b >= 5, .eligible = i % 37 != 0});
    }
    std::vector<int> colours;
    std::vector<std::uint32_t> scratch;
    ColourPairs(pairs, kBodies, colours, scratch);
    ASSERT_EQ(colours.size(), pairs.size());
    std::vector<std::set<int>> bodiesOf(kColourCount);
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const int colour = colours[i];
      ASSERT_GE(colour, 0);
      ASSERT_LE(colour, kOverflowColour);
      if (!pairs[i].eligible) {
        EXPECT_EQ(colour, kOverflowColour);
        continue;
      }
      if (colour == kOverflowColour) continue;
      for (const auto& [index, moves] :
           {std::pair{pairs[i].bodyA, pairs[i].movesA}, std::pair{pairs[i].bodyB, pairs[i].movesB}}) {
        if (!moves) continue;
        EXPECT_TRUE(bodiesOf[static_cast<std::size_t>(colour)].insert(index).second)
            << "body " << index << " twice in colour " << colour;
      }
    }
    std::vector<int> again;
    ColourPairs(pairs, kBodies, again, scratch);
    EXPECT_EQ(again, colours);
  }
}

TEST(ConstraintColouring, StaticBodiesDoNotCountAndABusyBodyOverflows) {
  // 40 pairs on one static body: one colour. 30 pairs on one movable body:
  // one per colour, then overflow.
  std::vector<ColourInput> pairs;
  for (int i = 0; i < 40; ++i) pairs.push_back({.bodyA = 1 + i, .bodyB = 0, .movesA = true, .movesB = false});
  for (int i = 0; i < 30; ++i)
    pairs.push_back({.bodyA = 41, .bodyB = 42 + i, .movesA = true, .movesB = true});
  std::vector<int> colours;
  std::vector<std::uint32_t> scratch;
  ColourPairs(pairs, 72, colours, scratch);
  for (int i = 0; i < 40; ++i) EXPECT_EQ(colours[static_cast<std::size_t>(i)], 0);
  // Pair 40 + k meets body 41, already in colours 0 .. k - 1 (and body 41
  // took no colour from the static pairs), so it takes colour k.
  for (int k = 0; k < 30; ++k) {
    EXPECT_EQ(colours[static_cast<std::size_t>(40 + k)], k < kColourCount ? k : kOverflowColour);
  }
}

// Boxes that touch only the ground: every pair shares no movable body, so
// the coloured order visits each pair with the same velocities as the
// scalar order, and each lane's arithmetic is the scalar solver's, in its
// order: the two solvers must agree to the last bit. Sliding, spinning,
// tilted, bouncing and frictionless boxes exercise every row kind, the
// block solve and its row-by-row fallback, and the extra sweeps.
WorldSettings SettingsFor(ContactOrder kind) {
  WorldSettings settings;
  settings.methods.contactOrder = kind;
  // The per-point friction rows both solvers have (the coloured one has no
  // coupled block; World::Create refuses it there).
  settings.methods.frictionSolve = FrictionSolve::PerPoint;
  return settings;
}

void AddLooseBoxes(ContactScene& scene) {
  scene.AddPlane({.normal = Vec3::UnitY(), .offset = 0.0, .friction = 0.6, .restitution = 0.0});
  for (int i = 0; i < 11; ++i) {
    const double x = 3.0 * i;
    const Vec3 half(0.3 + 0.05 * i, 0.25 + 0.02 * (i % 3), 0.4 - 0.02 * i);
    const Quat tilt(Eigen::AngleAxisd(0.05 * (i % 4), Vec3(1.0, 0.3 * i, 0.2).normalized()));
    const int body = scene.AddBox(Vec3(x, half.y() + 0.002 * (i % 5), 0.0), half, 1.0 + 0.7 * i, tilt,
                                  i == 7 ? 0.0 : 0.4, i == 3 ? 0.6 : 0.0);
    scene.Body(body).linearVelocity = Vec3(0.5 * (i % 3), -0.8 * (i % 2), 0.3);
    scene.Body(body).angularVelocity = Vec3(0.0, 0.7 * (i % 4), 0.1);
  }
}

TEST(ColouredSolver, PairsSharingNoMovableBodyMatchTheScalarSolverBitForBit) {
  ContactScene scalar(SettingsFor(ContactOrder::PairByPair));
  ContactScene wide(SettingsFor(ContactOrder::ByColour));
  AddLooseBoxes(scalar);
  AddLooseBoxes(wide);
  for (int step = 0; step < 240; ++step) {
    scalar.Step(kH);
    wide.Step(kH);
    ASSERT_EQ(HashState(scalar.Bodies()), HashState(wide.Bodies())) << "step " << step;
  }
  // The scene did what it was built for: 11 pairs in one colour (three
  // bundles, the last one partly empty), none in overflow.
  EXPECT_EQ(wide.LastStats().solverColours, 1);
  EXPECT_EQ(wide.LastStats().overflowPairs, 0);
  EXPECT_EQ(wide.Solver().Wide().BundleCount(0), 3);
}

// A small pyramid of boxes (box-box contacts through the narrow phase):
// several colours with many bundles each.
void AddPyramid(ContactScene& scene) {
  scene.EnableBoxPairs();
  scene.AddPlane({.normal = Vec3::UnitY(), .offset = 0.0, .friction = 0.5});
  const double half = 0.5;
  for (int layer = 0; layer < 4; ++layer) {
    const int side = 4 - layer;
    for (int j = 0; j < side; ++j) {
      for (int k = 0; k < side; ++k) {
        const Vec3 center(2.0 * half * j + layer * half, half + 2.0 * half * layer,
                          2.0 * half * k + layer * half);
        scene.AddBox(center, Vec3::Constant(half), 1000.0);
      }
    }
  }
}

// Runs the pyramid for `steps` with each phase cut into `cuts` ranges,
// optionally run in reverse order or on threads; returns the state hash.
std::uint64_t RunPyramid(int cuts, bool reverse, bool threads, int steps, StepStatistics* last = nullptr) {
  ContactScene scene(SettingsFor(ContactOrder::ByColour), 0.02);
  AddPyramid(scene);
  if (cuts > 0) {
    // Each phase (Prepare's pairs, the packing, each colour's bundles) cut
    // into `cuts` ranges, phase after phase as the contract says.
    scene.Solver().SetPhaseRunner(
        [=](std::span<const JobPhase> phases, const std::function<void(int, int, int)>& body) {
          for (std::size_t p = 0; p < phases.size(); ++p) {
            const int count = phases[p].count;
            std::vector<std::pair<int, int>> ranges;
            for (int c = 0; c < cuts; ++c) ranges.emplace_back(count * c / cuts, count * (c + 1) / cuts);
            if (reverse) std::reverse(ranges.begin(), ranges.end());
            const int phase = static_cast<int>(p);
            if (!threads) {
              for (const auto& [begin, end] : ranges) {
                if (begin < end) body(phase, begin, end);
              }
              continue;
            }
            std::vector<std::thread> workers;
            for (const auto& [begin, end] : ranges) {
              if (begin < end) workers.emplace_back([&body, phase, begin, end] { body(phase, begin, end); });
            }
            for (std::thread& worker : workers) worker.join();
          }
        });
  }
  for (int step = 0; step < steps; ++step) scene.Step(kH);
  if (last != nullptr) *last = scene.LastStats();
  return HashState(scene.Bodies());
}

TEST(ColouredSolver, AnyCutOfAColourIntoRangesGivesBitIdenticalStates) {
  constexpr int kSteps = 30;
  StepStatistics stats;
  const std::uint64_t whole = RunPyramid(0, false, false, kSteps, &stats);
  // The pyramid is coloured: more than one colour, so ranges cut real work.
  EXPECT_GT(stats.solverColours, 1);
  EXPECT_EQ(RunPyramid(1, false, false, kSteps), whole);
  EXPECT_EQ(RunPyramid(2, false, false, kSteps), whole);
  EXPECT_EQ(RunPyramid(3, false, false, kSteps), whole);
  EXPECT_EQ(RunPyramid(3, true, false, kSteps), whole);
  // On threads (one per range, started per colour pass, so fewer steps):
  // the first steps, where every pair is new and the extra sweeps run.
  constexpr int kThreadedSteps = 5;
  EXPECT_EQ(RunPyramid(3, false, true, kThreadedSteps), RunPyramid(0, false, false, kThreadedSteps));
}

TEST(ColouredSolver, PyramidStandsLikeTheScalarSolver) {
  // Physics, not bits: the coloured order must hold the 30-box pyramid as
  // the scalar order does. After 2 s every box is within 1 mm of where it
  // started (they are placed touching; the Baumgarte slop is 4 mm, so a box
  // that sinks by the slop in each of 4 layers would be 1.6 cm off) and at
  // rest to 1 cm/s.
  for (const ContactOrder kind : {ContactOrder::PairByPair, ContactOrder::ByColour}) {
    ContactScene scene(SettingsFor(kind), 0.02);
    AddPyramid(scene);
    std::vector<Vec3> start;
    for (const BodySim& body : scene.Bodies()) start.push_back(body.center);
    for (int step = 0; step < 120; ++step) scene.Step(kH);
    double moved = 0.0;
    double speed = 0.0;
    for (std::size_t i = 0; i < start.size(); ++i) {
      const BodySim& body = scene.Bodies()[i];
      if (body.type != BodyType::Dynamic) continue;
      moved = std::max(moved, (body.center - start[i]).norm());
      speed = std::max(speed, body.linearVelocity.norm());
    }
    EXPECT_LT(moved, 1e-3) << "solver " << static_cast<int>(kind);
    EXPECT_LT(speed, 1e-2) << "solver " << static_cast<int>(kind);
  }
}

TEST(ColouredSolver, PairsPastTheLastColourAreSolvedInTheOverflow) {
  // 30 small boxes on one large dynamic slab, the slab on the ground: all
  // 31 pairs share the slab, so 24 colours fill and 7 pairs overflow. They must rest as
  // well as the rest: after 1 s nothing moves faster than 1 cm/s.
  ContactScene scene(SettingsFor(ContactOrder::ByColour), 0.02);
  scene.EnableBoxPairs();
  scene.AddPlane({.normal = Vec3::UnitY(), .offset = 0.0, .friction = 0.5});
  scene.AddBox(Vec3(0.0, 0.25, 0.0), Vec3(4.0, 0.25, 4.0), 500.0);
  for (int i = 0; i < 30; ++i) {
    const Vec3 center(-3.5 + 1.0 * (i % 6), 0.5 + 0.2, -3.0 + 1.2 * (i / 6));
    scene.AddBox(center, Vec3::Constant(0.2), 10.0);
  }
  for (int step = 0; step < 60; ++step) scene.Step(kH);
  EXPECT_EQ(scene.LastStats().solverColours, kColourCount);
  EXPECT_EQ(scene.LastStats().overflowPairs, 7);
  double speed = 0.0;
  for (const BodySim& body : scene.Bodies()) speed = std::max(speed, body.linearVelocity.norm());
  EXPECT_LT(speed, 1e-2);
}

}  // namespace coloured_solver_test
}  // namespace talus
