// BroadPhase: validation at the boundary, the tiny-world shortcut, and
// dispatch to the selected structure (write-up section 2).
#include "collision/broad_phase.h"

#include <cmath>
#include <string>

namespace talus {
namespace {

// Why proxy `slot` cannot be used, or an empty string when it can.
std::string CheckProxy(const BroadPhaseProxy& p) {
  if (!p.active) return {};
  const Sphere& s = p.sphere;
  if (!s.center.allFinite()) return "centre is NaN or infinite";
  if (!std::isfinite(s.radius)) return "radius is NaN or infinite";
  if (s.radius < 0.0) return "radius " + std::to_string(s.radius) + " is negative";
  if (s.center.cwiseAbs().maxCoeff() > kMaxWorldCoordinate)
    return "centre coordinate beyond " + std::to_string(kMaxWorldCoordinate) + " m";
  if (s.radius > kMaxWorldCoordinate) return "radius beyond " + std::to_string(kMaxWorldCoordinate) + " m";
  return {};
}

}  // namespace

Result<int> BroadPhase::Update(std::span<const BroadPhaseProxy> proxies) {
  int active = 0;
  int statics = 0;
  for (std::size_t i = 0; i < proxies.size(); ++i) {
    const std::string problem = CheckProxy(proxies[i]);
    if (!problem.empty()) return Error{"broad phase proxy " + std::to_string(i) + ": " + problem};
    if (proxies[i].active) {
      ++active;
      if (proxies[i].isStatic) ++statics;
    }
  }
  m_proxies.assign(proxies.begin(), proxies.end());
  m_activeCount = active;
  m_staticCount = statics;
  return active;
}

void BroadPhase::FindPairs(std::vector<BroadPhasePair>& out, BroadPhaseStats& stats) {
  stats = BroadPhaseStats{};
  stats.proxyCount = m_activeCount;
  stats.staticProxyCount = m_staticCount;
  const BroadPhaseKind kind = m_activeCount <= m_tinyWorldProxies ? BroadPhaseKind::BruteForce : m_kind;
  stats.kindUsed = kind;
  switch (kind) {
    case BroadPhaseKind::UniformGrid:
      m_grid.FindPairs(m_proxies, out, stats);
      break;
    case BroadPhaseKind::AabbTree:
      m_tree.FindPairs(m_proxies, out, stats);
      break;
    case BroadPhaseKind::BruteForce:
      m_bruteForce.FindPairs(m_proxies, out, stats);
      break;
  }
}

}  // namespace talus
