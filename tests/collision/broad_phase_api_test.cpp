// The BroadPhase entry point: bad proxies refused with a message naming the
// slot (and nothing half-applied), the tiny-world path, determinism and the
// pair order the narrow phase relies on.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "collision/broad_phase.h"
#include "collision/broad_phase_test_worlds.h"

namespace talus {
namespace broad_phase_api_test {

using testing::MakeWorld;
using testing::OraclePairs;
using testing::SplitMix64;
using testing::StepWorld;
using testing::TestWorld;
using testing::WorldSpec;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A world of four touching balls with slot 2 replaced by `bad`; Update must
// refuse it, name slot 2 and the reason, and keep the previous proxies.
void ExpectRefused(const BroadPhaseProxy& bad, const std::string& reason) {
  std::vector<BroadPhaseProxy> good;
  for (int i = 0; i < 4; ++i) good.push_back({.sphere = {Vec3(0.5 * i, 0, 0), 0.5}});
  BroadPhase phase;
  ASSERT_TRUE(phase.Update(good));
  std::vector<BroadPhaseProxy> proxies = good;
  proxies[2] = bad;
  const Result<int> result = phase.Update(proxies);
  ASSERT_FALSE(result);
  const std::string& message = result.GetError().message;
  EXPECT_NE(message.find("proxy 2"), std::string::npos) << message;
  EXPECT_NE(message.find(reason), std::string::npos) << message;
  ASSERT_EQ(phase.Proxies().size(), good.size());
  std::vector<BroadPhasePair> pairs;
  BroadPhaseStats stats;
  phase.FindPairs(pairs, stats);
  EXPECT_EQ(pairs, OraclePairs(good)) << "the previous proxies stand";
}

TEST(BroadPhaseUpdate, RefusesNaNCentre) {
  ExpectRefused({.sphere = {Vec3(0, kNaN, 0), 1}}, "centre is NaN");
}
TEST(BroadPhaseUpdate, RefusesInfiniteCentre) { ExpectRefused({.sphere = {Vec3(kInf, 0, 0), 1}}, "centre"); }
TEST(BroadPhaseUpdate, RefusesNaNRadius) {
  ExpectRefused({.sphere = {Vec3(0, 0, 0), kNaN}}, "radius is NaN");
}
TEST(BroadPhaseUpdate, RefusesNegativeRadius) { ExpectRefused({.sphere = {Vec3(0, 0, 0), -1}}, "negative"); }
TEST(BroadPhaseUpdate, RefusesCentreBeyondWorldLimit) {
  ExpectRefused({.sphere = {Vec3(0, 0, 2 * kMaxWorldCoordinate), 1}}, "beyond");
}

TEST(BroadPhaseUpdate, IgnoresGarbageInInactiveSlots) {
  const std::vector<BroadPhaseProxy> proxies = {{.sphere = {Vec3(0, 0, 0), 1}},
                                                {.sphere = {Vec3(kNaN, 0, 0), -kInf}, .active = false},
                                                {.sphere = {Vec3(1, 0, 0), 1}}};
  BroadPhase phase;
  const Result<int> result = phase.Update(proxies);
  ASSERT_TRUE(result) << result.GetError().message;
  EXPECT_EQ(result.Value(), 2);
  std::vector<BroadPhasePair> pairs;
  BroadPhaseStats stats;
  phase.FindPairs(pairs, stats);
  EXPECT_EQ(pairs, (std::vector<BroadPhasePair>{{0, 2}}));
}

TEST(BroadPhaseTinyWorld, SmallWorldsTakeBruteForceLargeOnesTheSelectedKind) {
  for (const BroadPhaseKind kind : {BroadPhaseKind::UniformGrid, BroadPhaseKind::AabbTree}) {
    BroadPhase phase(kind);
    std::vector<BroadPhasePair> pairs;
    BroadPhaseStats stats;
    const TestWorld small = MakeWorld({.count = kTinyWorldProxies, .halfExtent = 2}, 1);
    ASSERT_TRUE(phase.Update(small.proxies));
    phase.FindPairs(pairs, stats);
    EXPECT_EQ(stats.kindUsed, BroadPhaseKind::BruteForce);
    EXPECT_EQ(pairs, OraclePairs(small.proxies));
    const TestWorld large = MakeWorld({.count = kTinyWorldProxies + 1, .halfExtent = 2}, 2);
    ASSERT_TRUE(phase.Update(large.proxies));
    phase.FindPairs(pairs, stats);
    EXPECT_EQ(stats.kindUsed, kind);
    EXPECT_EQ(pairs, OraclePairs(large.proxies));
  }
}

// Runs a moving world for `steps` and folds every pair and count into a hash.
std::uint64_t RunAndHash(BroadPhaseKind kind, int steps) {
  const WorldSpec spec{.count = 700, .halfExtent = 8, .minRadius = 0.1, .maxRadius = 2, .speed = 0.2};
  TestWorld world = MakeWorld(spec, 99);
  SplitMix64 rng(100);
  BroadPhase phase(kind);
  std::vector<BroadPhasePair> pairs;
  BroadPhaseStats stats;
  std::uint64_t hash = 1469598103934665603ull;
  auto mix = [&hash](std::uint64_t v) { hash = (hash ^ v) * 1099511628211ull; };
  for (int step = 0; step < steps; ++step) {
    EXPECT_TRUE(phase.Update(world.proxies));
    phase.FindPairs(pairs, stats);
    for (const BroadPhasePair& p : pairs)
      mix(static_cast<std::uint64_t>(p.a) << 32 | static_cast<std::uint32_t>(p.b));
    mix(static_cast<std::uint64_t>(stats.candidatePairs));
    mix(static_cast<std::uint64_t>(stats.occupiedCells));
    mix(static_cast<std::uint64_t>(stats.treeReinsertions));
    StepWorld(spec, world, rng);
  }
  return hash;
}

TEST(BroadPhaseDeterminism, SameInputsGiveSamePairsAndCounts) {
  for (const BroadPhaseKind kind :
       {BroadPhaseKind::UniformGrid, BroadPhaseKind::AabbTree, BroadPhaseKind::BruteForce}) {
    EXPECT_EQ(RunAndHash(kind, 10), RunAndHash(kind, 10)) << ToString(kind);
  }
}

TEST(BroadPhaseOrder, PairsAreStrictlyIncreasingWithLowerSlotFirst) {
  const TestWorld world = MakeWorld({.count = 2000, .halfExtent = 10, .minRadius = 0.2, .maxRadius = 2}, 5);
  for (const BroadPhaseKind kind : {BroadPhaseKind::UniformGrid, BroadPhaseKind::AabbTree}) {
    BroadPhase phase(kind);
    std::vector<BroadPhasePair> pairs;
    BroadPhaseStats stats;
    ASSERT_TRUE(phase.Update(world.proxies));
    phase.FindPairs(pairs, stats);
    ASSERT_GT(pairs.size(), 100u);
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      EXPECT_LT(pairs[i].a, pairs[i].b);
      if (i > 0) {
        EXPECT_LT(pairs[i - 1], pairs[i]);
      }
    }
  }
}

}  // namespace broad_phase_api_test
}  // namespace talus
