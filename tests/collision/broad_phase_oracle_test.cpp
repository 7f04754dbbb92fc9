// Every broad phase structure against the brute-force oracle: the same pair
// set, in the same order, on random worlds (uniform and mixed sizes, sparse
// and dense, static and oversized bodies, empty slots), moving over many
// steps while bodies are added, removed and switched static/dynamic.
#include <gtest/gtest.h>

#include <array>
#include <string>

#include "collision/broad_phase.h"
#include "collision/broad_phase_test_worlds.h"

namespace talus {
namespace broad_phase_oracle_test {

using testing::MakeWorld;
using testing::OraclePairs;
using testing::SplitMix64;
using testing::StepWorld;
using testing::TestWorld;
using testing::WorldSpec;

constexpr std::array<BroadPhaseKind, 3> kAllKinds = {BroadPhaseKind::UniformGrid, BroadPhaseKind::AabbTree,
                                                     BroadPhaseKind::BruteForce};

// The statistics every structure must satisfy, whatever its strategy.
void ExpectStatsAddUp(const BroadPhaseStats& stats, const std::vector<BroadPhasePair>& pairs,
                      const std::vector<BroadPhaseProxy>& proxies) {
  int active = 0;
  int statics = 0;
  for (const BroadPhaseProxy& p : proxies) {
    active += p.active ? 1 : 0;
    statics += p.active && p.isStatic ? 1 : 0;
  }
  EXPECT_EQ(stats.proxyCount, active);
  EXPECT_EQ(stats.staticProxyCount, statics);
  EXPECT_EQ(stats.spherePairs, static_cast<std::int64_t>(pairs.size()));
  EXPECT_LE(stats.spherePairs, stats.candidatePairs);
  EXPECT_LE(stats.oversizedTests, stats.candidatePairs);
  const std::int64_t n = active;
  const std::int64_t s = statics;
  EXPECT_LE(stats.candidatePairs, n * (n - 1) / 2 - s * (s - 1) / 2) << "a candidate pair counted twice";
  EXPECT_LE(stats.skippedStaticPairs, s * (s - 1) / 2);
}

struct OracleCase {
  std::string name;
  WorldSpec spec;
  int steps = 0;
};

// Names the case in failure messages instead of dumping its bytes.
void PrintTo(const OracleCase& c, std::ostream* os) { *os << c.name; }

class BroadPhaseOracle : public ::testing::TestWithParam<OracleCase> {};

TEST_P(BroadPhaseOracle, EveryKindReportsTheOraclePairsAtEveryStep) {
  const OracleCase& c = GetParam();
  TestWorld world = MakeWorld(c.spec, 1234567);
  SplitMix64 rng(987654321);
  std::array<BroadPhase, 3> phases = {BroadPhase(kAllKinds[0]), BroadPhase(kAllKinds[1]),
                                      BroadPhase(kAllKinds[2])};
  for (BroadPhase& phase : phases) phase.SetTinyWorldProxies(0);
  std::vector<BroadPhasePair> pairs;
  BroadPhaseStats stats;
  std::int64_t totalPairs = 0;
  for (int step = 0; step < c.steps; ++step) {
    const std::vector<BroadPhasePair> expected = OraclePairs(world.proxies);
    totalPairs += static_cast<std::int64_t>(expected.size());
    for (BroadPhase& phase : phases) {
      ASSERT_TRUE(phase.Update(world.proxies));
      phase.FindPairs(pairs, stats);
      ASSERT_EQ(pairs, expected) << ToString(phase.Kind()) << " at step " << step;
      EXPECT_EQ(stats.kindUsed, phase.Kind());
      ExpectStatsAddUp(stats, pairs, world.proxies);
      if (phase.Kind() == BroadPhaseKind::AabbTree) {
        ASSERT_TRUE(phase.Tree().IsValid()) << "step " << step;
        EXPECT_EQ(stats.skippedStaticPairs, 0);
      }
    }
    StepWorld(c.spec, world, rng);
  }
  // A world without pairs would make the comparison vacuous.
  EXPECT_GT(totalPairs, 10 * c.steps);
}

INSTANTIATE_TEST_SUITE_P(RandomWorlds, BroadPhaseOracle,
                         ::testing::Values(OracleCase{"UniformDense",
                                                      {.count = 1500,
                                                       .halfExtent = 8.0,
                                                       .minRadius = 0.5,
                                                       .maxRadius = 0.5,
                                                       .staticFraction = 0.1,
                                                       .speed = 0.05},
                                                      20},
                                           OracleCase{"UniformSparse",
                                                      {.count = 2000,
                                                       .halfExtent = 60.0,
                                                       .minRadius = 1.5,
                                                       .maxRadius = 1.5,
                                                       .staticFraction = 0.2,
                                                       .speed = 0.3},
                                                      20},
                                           OracleCase{"MixedSizesDense",
                                                      {.count = 1500,
                                                       .halfExtent = 15.0,
                                                       .minRadius = 0.05,
                                                       .maxRadius = 5.0,
                                                       .staticFraction = 0.2,
                                                       .speed = 0.1},
                                                      20},
                                           OracleCase{"MixedSizesSparse",
                                                      {.count = 1000,
                                                       .halfExtent = 300.0,
                                                       .minRadius = 0.1,
                                                       .maxRadius = 20.0,
                                                       .staticFraction = 0.1,
                                                       .speed = 1.0},
                                                      20},
                                           OracleCase{"FloorsAndWallsWithEmptySlots",
                                                      {.count = 1500,
                                                       .halfExtent = 10.0,
                                                       .minRadius = 0.3,
                                                       .maxRadius = 0.9,
                                                       .staticFraction = 0.05,
                                                       .oversizedStatics = 6,
                                                       .inactiveFraction = 0.2,
                                                       .speed = 0.1},
                                                      25},
                                           OracleCase{"AllStaticButFew",
                                                      {.count = 600,
                                                       .halfExtent = 5.0,
                                                       .minRadius = 0.5,
                                                       .maxRadius = 1.5,
                                                       .staticFraction = 0.97,
                                                       .speed = 0.05},
                                                      10},
                                           OracleCase{"FastBodiesCrossManyCells",
                                                      {.count = 1000,
                                                       .halfExtent = 5.0,
                                                       .minRadius = 0.2,
                                                       .maxRadius = 0.6,
                                                       .staticFraction = 0.1,
                                                       .speed = 1.5},
                                                      20}),
                         [](const ::testing::TestParamInfo<OracleCase>& info) { return info.param.name; });

TEST(BroadPhaseOracleLarge, TenThousandMixedBodiesWithFloorMatchOracle) {
  const WorldSpec spec{.count = 10000,
                       .halfExtent = 40.0,
                       .minRadius = 0.1,
                       .maxRadius = 4.0,
                       .staticFraction = 0.1,
                       .oversizedStatics = 3,
                       .inactiveFraction = 0.05,
                       .speed = 0.2};
  TestWorld world = MakeWorld(spec, 42);
  SplitMix64 rng(7);
  std::vector<BroadPhasePair> pairs;
  BroadPhaseStats stats;
  std::array<BroadPhase, 3> phases = {BroadPhase(kAllKinds[0]), BroadPhase(kAllKinds[1]),
                                      BroadPhase(kAllKinds[2])};
  for (int step = 0; step < 2; ++step) {
    const std::vector<BroadPhasePair> expected = OraclePairs(world.proxies);
    ASSERT_GT(expected.size(), 1000u);
    for (BroadPhase& phase : phases) {
      ASSERT_TRUE(phase.Update(world.proxies));
      phase.FindPairs(pairs, stats);
      ASSERT_EQ(pairs, expected) << ToString(phase.Kind()) << " at step " << step;
      ExpectStatsAddUp(stats, pairs, world.proxies);
    }
    StepWorld(spec, world, rng);
  }
}

}  // namespace broad_phase_oracle_test
}  // namespace talus
