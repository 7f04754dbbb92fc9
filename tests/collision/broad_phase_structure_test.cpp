// Properties of the individual structures: the grid's cell size rule, its
// multi-cell deduplication and oversized list; the tree's invariants, its
// enlarged boxes and balance; the analytic pair counts of brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "collision/broad_phase.h"
#include "collision/broad_phase_test_worlds.h"

namespace talus {
namespace broad_phase_structure_test {

using testing::MakeWorld;
using testing::OraclePairs;
using testing::SplitMix64;
using testing::StepWorld;
using testing::TestWorld;
using testing::WorldSpec;

BroadPhaseProxy Ball(const Vec3& center, double radius, bool isStatic = false) {
  return {.sphere = {center, radius}, .isStatic = isStatic, .active = true};
}

// Runs one step of `kind` with the tiny-world path off.
std::vector<BroadPhasePair> RunOnce(BroadPhaseKind kind, const std::vector<BroadPhaseProxy>& proxies,
                                    BroadPhaseStats& stats) {
  BroadPhase phase(kind);
  phase.SetTinyWorldProxies(0);
  EXPECT_TRUE(phase.Update(proxies));
  std::vector<BroadPhasePair> pairs;
  phase.FindPairs(pairs, stats);
  return pairs;
}

// The benchmark scenes' floor (docs/bench-scenes.md), box (50, 1, 50) at (0, -1, 0), under a layer of 1 m
// cubes (bounding radius sqrt(3)/2) resting on it.
std::vector<BroadPhaseProxy> FloorUnderCubes(int side) {
  std::vector<BroadPhaseProxy> proxies = {Ball({0, -1, 0}, std::sqrt(50.0 * 50 + 1 + 50.0 * 50), true)};
  for (int i = 0; i < side; ++i) {
    for (int k = 0; k < side; ++k)
      proxies.push_back(Ball({1.5 * i - 20, 0.5, 1.5 * k - 20}, std::sqrt(3.0) / 2));
  }
  return proxies;
}

TEST(UniformGrid, CellSizeFollowsLargestDynamicBodyNotTheFloor) {
  BroadPhaseStats stats;
  const auto proxies = FloorUnderCubes(10);
  const auto pairs = RunOnce(BroadPhaseKind::UniformGrid, proxies, stats);
  EXPECT_DOUBLE_EQ(stats.cellSize, kCellSizeFactor * std::sqrt(3.0));
  EXPECT_EQ(stats.oversizedProxies, 1);
  // The floor is tested against each of the 100 cubes exactly once.
  EXPECT_EQ(stats.oversizedTests, 100);
  EXPECT_EQ(pairs, OraclePairs(proxies));
  // Every cube touches the floor, and its axis neighbours 1.5 m away (< 2 x 0.866 m)
  // but not its diagonal ones (2.12 m): 100 + 2 x 10 x 9 pairs.
  EXPECT_EQ(std::count_if(pairs.begin(), pairs.end(), [](const BroadPhasePair& p) { return p.a == 0; }), 100);
  EXPECT_EQ(pairs.size(), 280u);
}

TEST(UniformGrid, DynamicBodyOverlapsAtMostEightCells) {
  SplitMix64 rng(5);
  BroadPhaseStats stats;
  for (int trial = 0; trial < 500; ++trial) {
    const double radius = rng.LogUniform(1e-3, 1e3);
    const Vec3 c{rng.Uniform(-1e4, 1e4), rng.Uniform(-1e4, 1e4), rng.Uniform(-1e4, 1e4)};
    RunOnce(BroadPhaseKind::UniformGrid, {Ball(c, radius)}, stats);
    EXPECT_GE(stats.occupiedCells, 1);
    EXPECT_LE(stats.occupiedCells, 8) << "radius " << radius;
  }
}

TEST(UniformGrid, PairSharingEightCellsIsCountedOnce) {
  // Radius 0.5 at a cell corner: cell size 1, each body spans 2x2x2 cells.
  BroadPhaseStats stats;
  const auto pairs =
      RunOnce(BroadPhaseKind::UniformGrid, {Ball({0, 0, 0}, 0.5), Ball({0, 0, 0}, 0.5)}, stats);
  EXPECT_EQ(stats.occupiedCells, 8);
  EXPECT_EQ(stats.candidatePairs, 1);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0], (BroadPhasePair{0, 1}));
}

TEST(UniformGrid, WorldWithoutDynamicBodiesBinsNothing) {
  BroadPhaseStats stats;
  const auto pairs =
      RunOnce(BroadPhaseKind::UniformGrid, {Ball({0, 0, 0}, 1, true), Ball({0, 0, 0}, 1, true)}, stats);
  EXPECT_TRUE(pairs.empty());
  EXPECT_EQ(stats.cellSize, 0.0);
  EXPECT_EQ(stats.occupiedCells, 0);
}

TEST(UniformGrid, WorldTooWideForCellKeysFallsBackToTheTree) {
  // 1 mm bodies (2 mm cells) spread over 2e8 m: 10^11 cells per axis, more
  // than 63 key bits; the step must still be exact.
  std::vector<BroadPhaseProxy> proxies;
  for (int i = 0; i < 40; ++i) {
    const double x = (i % 2 == 0 ? -1e8 : 1e8) + 0.0015 * (i / 4);
    const double z = (i % 4 < 2 ? -1e8 : 1e8);
    proxies.push_back(Ball({x, 0, z}, 1e-3));
  }
  BroadPhase phase(BroadPhaseKind::UniformGrid);
  phase.SetTinyWorldProxies(0);
  ASSERT_TRUE(phase.Update(proxies));
  std::vector<BroadPhasePair> pairs;
  BroadPhaseStats stats;
  phase.FindPairs(pairs, stats);
  EXPECT_EQ(stats.kindUsed, BroadPhaseKind::AabbTree);
  EXPECT_EQ(pairs.size(), 4u * 9u);
  EXPECT_EQ(pairs, OraclePairs(proxies));
}

TEST(BroadPhase, TouchingSpheresArePairedAndSeparatedOnesAreNot) {
  // Centres 1 m apart, radii 0.5 each: exactly touching (all exact in binary).
  for (const BroadPhaseKind kind :
       {BroadPhaseKind::UniformGrid, BroadPhaseKind::AabbTree, BroadPhaseKind::BruteForce}) {
    BroadPhaseStats stats;
    EXPECT_EQ(RunOnce(kind, {Ball({3, 7, -2}, 0.5), Ball({4, 7, -2}, 0.5)}, stats).size(), 1u)
        << ToString(kind);
    EXPECT_TRUE(RunOnce(kind, {Ball({3, 7, -2}, 0.5), Ball({4 + 1e-9, 7, -2}, 0.5)}, stats).empty())
        << ToString(kind);
  }
}

TEST(BroadPhase, StaticStaticPairsAreNeverReportedButCounted) {
  const std::vector<BroadPhaseProxy> proxies = {Ball({0, 0, 0}, 1, true), Ball({0.5, 0, 0}, 1, true),
                                                Ball({1, 0, 0}, 1)};
  for (const BroadPhaseKind kind :
       {BroadPhaseKind::UniformGrid, BroadPhaseKind::AabbTree, BroadPhaseKind::BruteForce}) {
    BroadPhaseStats stats;
    const auto pairs = RunOnce(kind, proxies, stats);
    EXPECT_EQ(pairs, (std::vector<BroadPhasePair>{{0, 2}, {1, 2}})) << ToString(kind);
    // The tree never visits static-static pairs; the others meet and drop it.
    EXPECT_EQ(stats.skippedStaticPairs, kind == BroadPhaseKind::AabbTree ? 0 : 1) << ToString(kind);
  }
}

TEST(BruteForceBroadPhase, CandidatesAreAllPairsButStaticStatic) {
  // Figure 2 of the write-up: 15 bodies; here 3 of them static.
  TestWorld world = MakeWorld({.count = 15, .halfExtent = 3, .staticFraction = 0}, 11);
  for (int i = 0; i < 3; ++i) world.proxies[static_cast<std::size_t>(i)].isStatic = true;
  BroadPhaseStats stats;
  RunOnce(BroadPhaseKind::BruteForce, world.proxies, stats);
  EXPECT_EQ(stats.candidatePairs, 15 * 14 / 2 - 3);
  EXPECT_EQ(stats.skippedStaticPairs, 3);
}

TEST(AabbTree, SmallMotionsKeepLeavesAndLargeOnesReinsert) {
  TestWorld world = MakeWorld({.count = 300, .halfExtent = 10, .staticFraction = 0}, 3);
  BroadPhase phase(BroadPhaseKind::AabbTree);
  std::vector<BroadPhasePair> pairs;
  BroadPhaseStats stats;
  ASSERT_TRUE(phase.Update(world.proxies));
  phase.FindPairs(pairs, stats);
  EXPECT_EQ(stats.treeReinsertions, 300);
  // Well inside the margin kTreeMarginFraction x radius: no leaf moves.
  for (auto& p : world.proxies) p.sphere.center.x() += 0.25 * kTreeMarginFraction * p.sphere.radius;
  ASSERT_TRUE(phase.Update(world.proxies));
  phase.FindPairs(pairs, stats);
  EXPECT_EQ(stats.treeReinsertions, 0);
  // Beyond the whole margin: every leaf is reinserted.
  for (auto& p : world.proxies)
    p.sphere.center.y() += 2 * (kTreeMarginFraction * p.sphere.radius + kTreeMarginAbsolute);
  ASSERT_TRUE(phase.Update(world.proxies));
  phase.FindPairs(pairs, stats);
  EXPECT_EQ(stats.treeReinsertions, 300);
  EXPECT_TRUE(phase.Tree().IsValid());
  EXPECT_EQ(pairs, OraclePairs(world.proxies));
}

TEST(AabbTree, HeightStaysLogarithmicForOrderedInsertion) {
  // Bodies inserted along a line in order: the worst case for an unbalanced tree.
  std::vector<BroadPhaseProxy> proxies;
  for (int i = 0; i < 4096; ++i) proxies.push_back(Ball({2.0 * i, 0, 0}, 0.5));
  BroadPhaseStats stats;
  RunOnce(BroadPhaseKind::AabbTree, proxies, stats);
  // log2(4096) = 12; rotations keep the height within a small factor of it.
  EXPECT_GE(stats.treeHeight, 12);
  EXPECT_LE(stats.treeHeight, 24);
}

TEST(AabbTree, StaysValidWhenSkippedForStepsThenResumed) {
  // The tree synchronises lazily: steps run by another kind are caught up.
  const WorldSpec spec{.count = 800, .halfExtent = 8, .minRadius = 0.2, .maxRadius = 1.2, .speed = 0.3};
  TestWorld world = MakeWorld(spec, 77);
  SplitMix64 rng(78);
  BroadPhase phase(BroadPhaseKind::AabbTree);
  phase.SetTinyWorldProxies(0);
  std::vector<BroadPhasePair> pairs;
  BroadPhaseStats stats;
  for (int step = 0; step < 12; ++step) {
    phase.SetKind(step % 4 < 2 ? BroadPhaseKind::AabbTree : BroadPhaseKind::UniformGrid);
    ASSERT_TRUE(phase.Update(world.proxies));
    phase.FindPairs(pairs, stats);
    ASSERT_EQ(pairs, OraclePairs(world.proxies)) << "step " << step;
    EXPECT_TRUE(phase.Tree().IsValid());
    StepWorld(spec, world, rng);
  }
}

}  // namespace broad_phase_structure_test
}  // namespace talus
