// AabbTree: a dynamic bounding volume hierarchy of enlarged boxes, the broad
// phase for mixed body sizes and sparse worlds, where a uniform grid suffers
// (its cell size is set by the largest dynamic body, so a few big bodies make
// every cell crowded, and a sparse world spreads over many cells). Measured:
// it does prune 3-12x more candidates, but the grid stays faster in every
// moving scene of bench/broad_phase.cpp (docs/collision-broad-phase.md).
//
// Why a tree and not sweep-and-prune: sweep-and-prune projects on one axis,
// so in a flat dense layer (a floor covered with cubes) every body's interval
// overlaps a whole row of others and the sweep degrades towards O(n^2); the
// tree prunes in all three axes, and its cost depends on neither the world's
// extent nor the spread of sizes.
//
// Owns a binary tree in a node pool (indices, free list): each leaf holds one
// proxy's box enlarged by a margin (kTreeMarginFraction x radius +
// kTreeMarginAbsolute), each internal node the union of its two children's
// boxes and its height (leaf 0). Insertion descends by the surface area
// heuristic and, on the way up, rotates where swapping a child with a
// grandchild shrinks the surface area (the scheme of Box2D v3's tree; AVL
// height rotations, tried first, kept it shallow but made its boxes loose). A body keeps its leaf
// while its exact box stays inside the enlarged one, so a step of small
// motions touches few leaves. The tree is synchronised lazily from the proxy
// array (diff against its own copy of each slot's state), so slots added,
// removed or switched static/dynamic since the last call are all caught.
// Pairs are found by one simultaneous descent of the tree against itself
// (pairs of subtrees whose boxes overlap, splitting the taller), which meets
// each overlapping pair of leaves once; it costs far less than one query per
// body, whose random walks through the node pool miss the cache at 100k
// bodies. Each node knows whether its subtree holds a dynamic body, and two
// subtrees without one are never descended, so static-static pairs are never
// visited.
#pragma once

#include <span>
#include <utility>
#include <vector>

#include "collision/broad_phase_proxy.h"
#include "talus/broad_phase.h"

namespace talus {

class AabbTree {
 public:
  /// Synchronises the tree with `proxies`, then appends to `out` (cleared
  /// first) every pair of active proxies, not both static, whose spheres
  /// touch, sorted by (a, b). Fills candidatePairs, spherePairs,
  /// skippedStaticPairs (always 0), treeReinsertions and treeHeight.
  void FindPairs(std::span<const BroadPhaseProxy> proxies, std::vector<BroadPhasePair>& out,
                 BroadPhaseStats& stats);

  /// Height of the tree (0 for a single leaf or an empty tree).
  [[nodiscard]] int Height() const;

  /// Leaves currently in the tree.
  [[nodiscard]] int LeafCount() const { return m_leafCount; }

  /// Checks every structural invariant (parent and child links agree, each
  /// internal box contains its children's, heights consistent, every leaf's
  /// box contains its proxy's exact box); for tests.
  [[nodiscard]] bool IsValid() const;

 private:
  static constexpr int kNull = -1;

  struct Node {
    Aabb box;
    int parent = kNull;  ///< parent node, or next free node while free
    int child1 = kNull;
    int child2 = kNull;
    int proxy = kNull;        ///< slot for a leaf, kNull for an internal node
    int height = 0;           ///< leaf 0; -1 while free
    bool hasDynamic = false;  ///< some leaf below is a dynamic body
    [[nodiscard]] bool IsLeaf() const { return child1 == kNull; }
  };
  // The pair query descends node by node; a node spans at most two cache
  // lines (docs/collision-broad-phase.md, Record sizes).
  static_assert(sizeof(Node) == 72, "AabbTree::Node: 48-byte box, five ints and a flag");

  /// Inserts, removes or reinserts leaves so the tree matches `proxies`.
  /// Returns the number of leaves (re)inserted or removed.
  int Sync(std::span<const BroadPhaseProxy> proxies);
  int AllocateNode();
  void FreeNode(int node);
  void InsertLeaf(int leaf);
  void RemoveLeaf(int leaf);
  /// Recomputes an internal node's box, height and dynamic flag from its children.
  void Refit(int node);
  /// Restores boxes and heights from `node` to the root, rotating as it goes.
  void RefitUpwards(int node);
  /// Swaps a child of `a` with a grandchild when that shrinks the surface
  /// area of the subtree that changes (a's own box is unchanged).
  void Rotate(int a);
  /// Appends the pairs of leaves whose exact boxes overlap and spheres touch.
  void SelfPairs(std::span<const BroadPhaseProxy> proxies, std::vector<BroadPhasePair>& out,
                 std::int64_t& candidates);
  bool IsValidSubtree(int node, int parent) const;

  std::vector<Node> m_nodes;
  int m_root = kNull;
  int m_freeList = kNull;
  int m_leafCount = 0;
  std::vector<int> m_leafOfSlot;             ///< per slot: its leaf node, or kNull
  std::vector<Aabb> m_exactBox;              ///< per slot: exact (padded sphere) box
  std::vector<char> m_slotStatic;            ///< per slot: static flag at insertion
  std::vector<std::pair<int, int>> m_stack;  ///< traversal scratch: node pairs
};

}  // namespace talus
