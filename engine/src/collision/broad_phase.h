// BroadPhase: the one entry point the world calls each step, in two stages:
// Update(proxies) validates and takes a copy of the bounding spheres (slot i
// is body slot i), FindPairs(out, stats) lists the pairs whose spheres touch,
// static-static pairs excluded, sorted by (a, b) with a < b.
//
// Owns the three structures (only the selected one does work; the others
// keep empty buffers) and the proxy copy. Worlds with at most
// TinyWorldProxies() active proxies take the brute force path whatever the
// selection: for them a grid or tree costs more than it saves. Every
// structure yields the same pair set, so the choice only changes speed and
// the statistics. Buffers keep their capacity: a steady-state step allocates
// nothing. Invariant: after a failed Update the previous proxies stand.
#pragma once

#include <span>
#include <vector>

#include "collision/aabb_tree.h"
#include "collision/broad_phase_proxy.h"
#include "collision/brute_force_broad_phase.h"
#include "collision/uniform_grid.h"
#include "talus/broad_phase.h"
#include "talus/result.h"

namespace talus {

class BroadPhase {
 public:
  /// A broad phase using `kind` (default UniformGrid, the write-up's choice).
  explicit BroadPhase(BroadPhaseKind kind = BroadPhaseKind::UniformGrid) : m_kind(kind) {}

  /// The selected structure.
  [[nodiscard]] BroadPhaseKind Kind() const { return m_kind; }
  /// Selects another structure; takes effect at the next FindPairs.
  void SetKind(BroadPhaseKind kind) { m_kind = kind; }

  /// Worlds with at most this many active proxies use brute force (default
  /// kTinyWorldProxies; 0 disables the tiny-world path). Valid range >= 0.
  [[nodiscard]] int TinyWorldProxies() const { return m_tinyWorldProxies; }
  void SetTinyWorldProxies(int count) { m_tinyWorldProxies = count < 0 ? 0 : count; }

  /// Takes this step's proxies, slot i being body slot i. Refuses, leaving
  /// the previous proxies in place, a centre or radius that is NaN or
  /// infinite, a negative radius, or a value beyond kMaxWorldCoordinate
  /// (metres), naming the slot. Returns the number of active proxies.
  Result<int> Update(std::span<const BroadPhaseProxy> proxies);

  /// Replaces `out` with the pairs of the proxies of the last successful
  /// Update whose spheres touch, not both static, sorted by (a, b), a < b;
  /// `stats` is overwritten with this step's counts.
  void FindPairs(std::vector<BroadPhasePair>& out, BroadPhaseStats& stats);

  /// The proxies of the last successful Update.
  [[nodiscard]] std::span<const BroadPhaseProxy> Proxies() const { return m_proxies; }

  /// The tree structure, for tests of its invariants.
  [[nodiscard]] const AabbTree& Tree() const { return m_tree; }

 private:
  BroadPhaseKind m_kind;
  int m_tinyWorldProxies = kTinyWorldProxies;
  std::vector<BroadPhaseProxy> m_proxies;
  int m_activeCount = 0;
  int m_staticCount = 0;
  BruteForceBroadPhase m_bruteForce;
  UniformGrid m_grid;
  AabbTree m_tree;
};

}  // namespace talus
