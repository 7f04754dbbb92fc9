// MethodSettings::forceBroadPhase: a small world (at most kTinyWorldProxies
// bodies, where the default takes brute force) runs the selected structure,
// finds exactly the pairs of an all-pairs bounding-sphere test written here,
// and therefore steps bit for bit like the brute-force world. The oracle
// shares nothing with the engine's broad phase but the bounding sphere each
// shape declares (Shape::LocalBoundingSphere, public) and the speculative
// margin every proxy is grown by (MethodSettings::narrowPhase).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "support/same_bits.h"
#include "talus/harness/support/split_mix64.h"
#include "talus/world.h"

namespace talus {
namespace forced_broad_phase_test {

using testing_support::SameBits;

constexpr double kStep = 1.0 / 60.0;
constexpr int kSteps = 20;
constexpr int kWorlds = 8;

// One random body: a sphere or a box, static or dynamic, moving.
struct RandomBody {
  BodyDef def;
  double radius = 0.0;  // the shape's bounding-sphere radius (m)
};

std::vector<RandomBody> RandomBodies(std::uint64_t seed) {
  harness::SplitMix64 random(seed);
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * random.NextUniform(); };
  // 2 to 128 bodies: the whole range the default sends to brute force.
  const int count = 2 + static_cast<int>(random.NextUniform() * 127.0);
  // A cube of side ~1.2 m per body cubed: some spheres touch, most do not.
  const double half = 0.6 * std::cbrt(static_cast<double>(count));
  std::vector<RandomBody> bodies;
  for (int i = 0; i < count; ++i) {
    RandomBody body;
    body.def.type = random.NextUniform() < 0.15 ? BodyType::Static : BodyType::Dynamic;
    body.def.position = {uniform(-half, half), uniform(-half, half), uniform(-half, half)};
    if (body.def.type == BodyType::Dynamic) {
      body.def.linearVelocity = {uniform(-2, 2), uniform(-2, 2), uniform(-2, 2)};
      body.def.angularVelocity = {uniform(-3, 3), uniform(-3, 3), uniform(-3, 3)};
      body.def.density = 1000.0;
    }
    body.def.allowSleep = false;
    body.def.shape =
        random.NextUniform() < 0.5
            ? Shape::CreateSphere(uniform(0.1, 0.5)).Value()
            : Shape::CreateBox({uniform(0.1, 0.4), uniform(0.1, 0.4), uniform(0.1, 0.4)}).Value();
    body.radius = body.def.shape->LocalBoundingSphere().radius;
    EXPECT_EQ(body.def.shape->LocalBoundingSphere().center, Vec3::Zero())
        << "the oracle assumes centred shapes";
    bodies.push_back(std::move(body));
  }
  return bodies;
}

// The oracle: every pair of bodies, not both static, whose bounding spheres
// grown by `margin` touch (closed test), from the positions the world
// reports before the step.
std::int64_t OraclePairCount(const World& world, const std::vector<BodyId>& ids,
                             const std::vector<RandomBody>& bodies, double margin) {
  std::int64_t pairs = 0;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const Vec3 pi = world.GetBodyState(ids[i]).Value().position;
    for (std::size_t j = i + 1; j < ids.size(); ++j) {
      if (bodies[i].def.type == BodyType::Static && bodies[j].def.type == BodyType::Static) continue;
      const Vec3 pj = world.GetBodyState(ids[j]).Value().position;
      const double reach = (bodies[i].radius + margin) + (bodies[j].radius + margin);
      if ((pi - pj).squaredNorm() <= reach * reach) ++pairs;
    }
  }
  return pairs;
}

struct Configuration {
  const char* name;
  BroadPhaseKind selected;
  bool force;
  BroadPhaseKind expectedUsed;
};

TEST(ForcedBroadPhase, SmallWorldsRunTheForcedStructureAndFindTheOraclePairs) {
  const std::array<Configuration, 3> configurations = {{
      {"default (grid selected, not forced)", BroadPhaseKind::UniformGrid, false, BroadPhaseKind::BruteForce},
      {"forced grid", BroadPhaseKind::UniformGrid, true, BroadPhaseKind::UniformGrid},
      {"forced tree", BroadPhaseKind::AabbTree, true, BroadPhaseKind::AabbTree},
  }};
  std::int64_t oracleTotal = 0;
  std::int64_t gridCandidates = 0;
  std::int64_t bruteCandidates = 0;
  for (int w = 0; w < kWorlds; ++w) {
    const std::vector<RandomBody> bodies = RandomBodies(0xB80AD + static_cast<std::uint64_t>(w));
    std::vector<World> worlds;
    std::vector<std::vector<BodyId>> ids(configurations.size());
    for (std::size_t c = 0; c < configurations.size(); ++c) {
      WorldSettings settings;
      settings.gravity = Vec3::Zero();
      settings.sleeping = false;
      settings.broadPhase = configurations[c].selected;
      settings.methods.forceBroadPhase = configurations[c].force;
      // The oracle grows each sphere by the fixed margin; speculative
      // motion (the default) would grow it by each body's reach as well.
      settings.methods.speculativeMotion = false;
      worlds.push_back(World::Create(settings).Value());
      for (const RandomBody& body : bodies) ids[c].push_back(worlds[c].CreateBody(body.def).Value());
    }
    const double margin = worlds[0].Settings().methods.narrowPhase.speculativeMargin;
    for (int step = 0; step < kSteps; ++step) {
      const std::int64_t expected = OraclePairCount(worlds[0], ids[0], bodies, margin);
      oracleTotal += expected;
      for (std::size_t c = 0; c < configurations.size(); ++c) {
        const auto stats = worlds[c].Step(kStep);
        ASSERT_TRUE(stats) << stats.GetError().message;
        const BroadPhaseStats& bp = stats.Value().broadPhase;
        const std::string where = std::string(configurations[c].name) + ", world " + std::to_string(w) +
                                  " (" + std::to_string(bodies.size()) + " bodies), step " +
                                  std::to_string(step);
        EXPECT_EQ(bp.kindUsed, configurations[c].expectedUsed) << where;
        EXPECT_EQ(bp.spherePairs, expected) << where;
        if (configurations[c].expectedUsed == BroadPhaseKind::UniformGrid)
          gridCandidates += bp.candidatePairs;
        if (configurations[c].expectedUsed == BroadPhaseKind::BruteForce)
          bruteCandidates += bp.candidatePairs;
      }
      // The same pairs in the same order: the same step, bit for bit.
      for (std::size_t c = 1; c < configurations.size(); ++c) {
        for (std::size_t b = 0; b < bodies.size(); ++b) {
          ASSERT_TRUE(
              SameBits(worlds[0].GetBodyState(ids[0][b]).Value(), worlds[c].GetBodyState(ids[c][b]).Value()))
              << configurations[c].name << ", world " << w << ", body " << b << ", after step " << step;
        }
      }
    }
  }
  // The worlds are not trivial (pairs were found), and the grid really did
  // its own work: it met fewer candidates than all pairs.
  EXPECT_GT(oracleTotal, 100);
  EXPECT_LT(gridCandidates, bruteCandidates);
}

TEST(ForcedBroadPhase, AnUnknownStructureIsRefusedWithTheFieldNamed) {
  WorldSettings settings;
  // 3 lies in the enum's value range (two bits) but names no structure.
  settings.broadPhase = static_cast<BroadPhaseKind>(3);
  const auto world = World::Create(settings);
  ASSERT_FALSE(world);
  EXPECT_NE(world.GetError().message.find("WorldSettings.broadPhase = 3"), std::string::npos)
      << world.GetError().message;
}

}  // namespace forced_broad_phase_test
}  // namespace talus
