// Broad phase selection and per-step statistics (section 2 of the original
// write-up, "Broad phase - Bounding Spheres and Uniform Grids").
//
// The broad phase turns the bodies' bounding spheres into the list of body
// pairs the narrow phase must test. Every structure reports the same pairs
// (those whose bounding spheres touch, static-static pairs excluded), sorted
// by (a, b) with a < b; they differ only in how much work they do to find
// them, which BroadPhaseStats counts the way figure 2 of the write-up does.
#pragma once

#include <cstdint>

namespace talus {

/// Which structure finds the candidate pairs. Default: UniformGrid (the
/// write-up's choice). Worlds with at most a handful of bodies take the brute
/// force path whatever is selected, unless MethodSettings::forceBroadPhase
/// (see BroadPhaseStats::kindUsed and docs/collision-broad-phase.md for the
/// crossover).
enum class BroadPhaseKind {
  /// Sparse uniform grid (memory follows the occupied cells) whose cell size
  /// follows the dynamic bodies' bounding-sphere diameters; very large bodies
  /// go to an "oversized" list tested against every body. The fastest kind
  /// in every moving scene measured, mixed sizes and sparse worlds included.
  UniformGrid,
  /// Dynamic AABB tree (bounding volume hierarchy of slightly enlarged
  /// boxes, updated incrementally). Prunes 3-12x more candidates than the
  /// grid and is fastest for static sparse worlds up to ~1k bodies, but
  /// slower than the grid elsewhere; handles any world extent.
  AabbTree,
  /// Every pair tested: O(n^2). The reference the others are checked against.
  BruteForce,
};

/// Worlds with at most this many active bodies run brute force whatever
/// structure is selected, unless MethodSettings::forceBroadPhase: below it
/// brute force is measured faster (docs/collision-broad-phase.md).
inline constexpr int kTinyWorldBodies = 128;

/// Work done by one broad phase step. Counts are for that step only.
/// Invariants: spherePairs <= candidatePairs; oversizedTests <= candidatePairs.
struct BroadPhaseStats {
  /// The structure that actually ran this step: the selected kind, or
  /// BruteForce when the world was small enough for the tiny-world path, or
  /// AabbTree when the grid was selected but the occupied cells spanned more
  /// than its 63-bit cell keys can address (about 2^21 cells per axis).
  BroadPhaseKind kindUsed = BroadPhaseKind::BruteForce;
  /// Bodies taking part this step (active proxies), and how many are static.
  std::int64_t proxyCount = 0;
  std::int64_t staticProxyCount = 0;
  /// Pairs that reached the sphere-sphere test: those sharing a grid cell,
  /// whose boxes overlap in the tree, or every non static-static pair for
  /// brute force; plus the oversized tests. Each pair counted once.
  std::int64_t candidatePairs = 0;
  /// Pairs whose bounding spheres touch: what the narrow phase receives.
  std::int64_t spherePairs = 0;
  /// Static-static pairs met by the structure and dropped before the sphere
  /// test (the tree never visits them, so it reports 0).
  std::int64_t skippedStaticPairs = 0;
  /// Grid only: bodies too large for the grid, kept in the oversized list.
  std::int64_t oversizedProxies = 0;
  /// Grid only: sphere tests of an oversized body against another body.
  std::int64_t oversizedTests = 0;
  /// Grid only: cell edge length used this step (metres), 0 otherwise.
  double cellSize = 0.0;
  /// Grid only: cells holding at least one binned body this step.
  std::int64_t occupiedCells = 0;
  /// Tree only: leaves reinserted because their body left its enlarged box
  /// (or was added, removed or changed between static and dynamic).
  std::int64_t treeReinsertions = 0;
  /// Tree only: height of the tree after the update (a leaf alone is 0).
  std::int64_t treeHeight = 0;
};

/// A readable name for a kind ("uniform_grid", "aabb_tree", "brute_force").
constexpr const char* ToString(BroadPhaseKind kind) {
  switch (kind) {
    case BroadPhaseKind::UniformGrid:
      return "uniform_grid";
    case BroadPhaseKind::AabbTree:
      return "aabb_tree";
    case BroadPhaseKind::BruteForce:
      return "brute_force";
  }
  return "unknown";
}

}  // namespace talus
