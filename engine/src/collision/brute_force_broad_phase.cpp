// Brute force broad phase: the write-up's "210 sphere-sphere tests for 15
// bodies" baseline (figure 2), kept as the oracle and the tiny-world path.
#include "collision/brute_force_broad_phase.h"

#include <cstdint>

namespace talus {

void BruteForceBroadPhase::FindPairs(std::span<const BroadPhaseProxy> proxies,
                                     std::vector<BroadPhasePair>& out, BroadPhaseStats& stats) {
  out.clear();
  m_active.clear();
  std::int64_t staticCount = 0;
  for (std::size_t i = 0; i < proxies.size(); ++i) {
    if (!proxies[i].active) continue;
    m_active.push_back(static_cast<int>(i));
    if (proxies[i].isStatic) ++staticCount;
  }

  // Static-static pairs are never looked at; their number is known.
  stats.skippedStaticPairs = staticCount * (staticCount - 1) / 2;
  std::int64_t candidates = 0;
  const std::size_t n = m_active.size();
  for (std::size_t i = 0; i < n; ++i) {
    const BroadPhaseProxy& a = proxies[static_cast<std::size_t>(m_active[i])];
    for (std::size_t j = i + 1; j < n; ++j) {
      const BroadPhaseProxy& b = proxies[static_cast<std::size_t>(m_active[j])];
      if (a.isStatic && b.isStatic) continue;
      ++candidates;
      if (SpheresTouch(a.sphere, b.sphere)) out.push_back({m_active[i], m_active[j]});
    }
  }
  stats.candidatePairs = candidates;
  stats.spherePairs = static_cast<std::int64_t>(out.size());
}

}  // namespace talus
