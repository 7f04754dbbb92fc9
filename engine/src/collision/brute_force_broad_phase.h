// BruteForceBroadPhase: every pair of active proxies, O(n^2).
//
// The reference the grid and the tree are checked against, and the path for
// tiny worlds (kTinyWorldProxies), where it beats any structure. It owns only
// a scratch list of active slots, reused from step to step, so it allocates
// nothing in steady state. Pairs come out already in (a, b) order because
// both loops run over increasing slots.
#pragma once

#include <span>
#include <vector>

#include "collision/broad_phase_proxy.h"
#include "talus/broad_phase.h"

namespace talus {

class BruteForceBroadPhase {
 public:
  /// Appends to `out` (cleared first) every pair of active proxies, not both
  /// static, whose spheres touch, sorted by (a, b). Fills candidatePairs,
  /// spherePairs and skippedStaticPairs of `stats`.
  void FindPairs(std::span<const BroadPhaseProxy> proxies, std::vector<BroadPhasePair>& out,
                 BroadPhaseStats& stats);

 private:
  std::vector<int> m_active;  ///< active slots, increasing
};

}  // namespace talus
