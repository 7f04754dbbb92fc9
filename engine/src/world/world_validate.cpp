// The validation pass; see world/world_validate.h.
#include "world/world_validate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <string>
#include <vector>

namespace talus {
namespace {

std::string Pair(const Contact& c) {
  return std::string("(") + std::to_string(c.bodyA) + ", " + std::to_string(c.bodyB) + ")";
}

bool Live(const WorldData& d, int body) {
  return body >= 0 && static_cast<std::size_t>(body) < d.records.size() &&
         d.records[static_cast<std::size_t>(body)].alive;
}

// The unordered pair's key: (min, max).
std::uint64_t UnorderedKey(const Contact& c) {
  return PairKey(std::min(c.bodyA, c.bodyB), std::max(c.bodyA, c.bodyB));
}

int FindRoot(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    parent[static_cast<std::size_t>(i)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    i = parent[static_cast<std::size_t>(i)];
  }
  return i;
}

}  // namespace

std::string CheckContactGraph(const WorldData& d) {
  if (d.contactAnchors.size() != d.contacts.size()) {
    return std::string("contact graph: ") + std::to_string(d.contacts.size()) + " contacts but " +
           std::to_string(d.contactAnchors.size()) + " anchor records (one per contact)";
  }
  std::vector<std::uint64_t> unordered;
  unordered.reserve(d.contacts.size());
  for (std::size_t i = 0; i < d.contacts.size(); ++i) {
    const Contact& c = d.contacts[i];
    const std::string where = std::string("contact graph: contact ") + std::to_string(i) + " " + Pair(c);
    if (!Live(d, c.bodyA) || !Live(d, c.bodyB)) return where + " names a body that is not live";
    if (c.bodyA == c.bodyB) return where + " joins a body to itself";
    if (d.sims[static_cast<std::size_t>(c.bodyA)].type != BodyType::Dynamic &&
        d.sims[static_cast<std::size_t>(c.bodyB)].type != BodyType::Dynamic) {
      return where + " joins two bodies neither of which is dynamic";
    }
    if (c.manifold.pointCount < 0 || c.manifold.pointCount > kMaxManifoldPoints) {
      return where + " has " + std::to_string(c.manifold.pointCount) + " points (0 to " +
             std::to_string(kMaxManifoldPoints) + ")";
    }
    if (i > 0 && d.contacts[i - 1].PairKey() >= c.PairKey()) {
      return where + " is not after contact " + std::to_string(i - 1) + " " + Pair(d.contacts[i - 1]) +
             " in pair-key order (sorted, each pair once)";
    }
    unordered.push_back(UnorderedKey(c));
  }
  std::sort(unordered.begin(), unordered.end());
  if (const auto twice = std::adjacent_find(unordered.begin(), unordered.end()); twice != unordered.end()) {
    return std::string("contact graph: bodies ") + std::to_string(*twice >> 32) + " and " +
           std::to_string(*twice & 0xffffffffu) + " have two contacts (each pair once)";
  }
  for (std::size_t i = 1; i < d.satCaches.size(); ++i) {
    if (d.satCaches[i - 1].pairKey >= d.satCaches[i].pairKey) {
      return std::string("contact graph: SAT cache ") + std::to_string(i) + " (key " +
             std::to_string(d.satCaches[i].pairKey) + ") is not after cache " + std::to_string(i - 1) +
             " in pair-key order (sorted, each pair once)";
    }
  }
  return {};
}

std::string CheckIslands(const WorldData& d, std::int64_t islands) {
  const auto dynamic = [&d](int body) {
    return d.sims[static_cast<std::size_t>(body)].type == BodyType::Dynamic;
  };
  for (std::size_t i = 0; i < d.sims.size(); ++i) {
    const BodySim& body = d.sims[i];
    if (!d.records[i].alive || body.type != BodyType::Dynamic || body.awake) continue;
    if (!d.settings.sleeping) {
      return std::string("islands: body ") + std::to_string(i) + " sleeps in a world without sleeping";
    }
    if (body.linearVelocity.any() || body.angularVelocity.any()) {
      return std::string("islands: body ") + std::to_string(i) + " sleeps with a velocity";
    }
  }
  if (!d.settings.sleeping) return {};

  std::vector<int> parent(d.sims.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (const Contact& c : d.contacts) {
    if (!dynamic(c.bodyA) || !dynamic(c.bodyB)) continue;
    const bool awakeA = d.sims[static_cast<std::size_t>(c.bodyA)].awake;
    if (awakeA != d.sims[static_cast<std::size_t>(c.bodyB)].awake) {
      return std::string("islands: contact ") + Pair(c) + " joins awake body " +
             std::to_string(awakeA ? c.bodyA : c.bodyB) + " to sleeping body " +
             std::to_string(awakeA ? c.bodyB : c.bodyA) + " (an island sleeps and wakes whole)";
    }
    const int ra = FindRoot(parent, c.bodyA);
    const int rb = FindRoot(parent, c.bodyB);
    if (ra != rb) parent[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
  }
  std::int64_t awakeIslands = 0;
  for (std::size_t i = 0; i < d.sims.size(); ++i) {
    const BodySim& body = d.sims[i];
    if (!d.records[i].alive || body.type != BodyType::Dynamic || !body.awake) continue;
    if (FindRoot(parent, static_cast<int>(i)) == static_cast<int>(i)) ++awakeIslands;
  }
  if (awakeIslands != islands) {
    return std::string("islands: the contacts join the awake bodies into ") + std::to_string(awakeIslands) +
           std::string(" islands, the sleep pass counted ") + std::to_string(islands);
  }
  return {};
}

std::string CheckBroadPhase(const WorldData& d, BroadPhaseKind used) {
  const std::span<const BroadPhaseProxy> proxies = d.broadPhase.Proxies();
  if (proxies.size() != d.records.size()) {
    return std::string("broad phase: ") + std::to_string(proxies.size()) + " proxies for " +
           std::to_string(d.records.size()) + " body slots (one per slot)";
  }
  for (std::size_t i = 0; i < proxies.size(); ++i) {
    // A live body with a shape has an active proxy; an empty slot or a
    // body without a shape (it collides with nothing) has none.
    const bool collides = d.records[i].alive && d.shapes[i].has_value();
    if (proxies[i].active != collides) {
      return std::string("broad phase: body ") + std::to_string(i) + "'s proxy is " +
             (proxies[i].active ? "active, but the body is not live or has no shape"
                                : "inactive, but the body is live and has a shape");
    }
    const Sphere& s = proxies[i].sphere;
    if (!s.center.allFinite() || !std::isfinite(s.radius) || s.radius < 0.0) {
      return std::string("broad phase: body ") + std::to_string(i) + "'s proxy is not finite";
    }
  }
  if (used == BroadPhaseKind::AabbTree && !d.broadPhase.Tree().IsValid()) {
    return "broad phase: the AABB tree breaks its links, heights or boxes (AabbTree::IsValid)";
  }
  return {};
}

std::string CheckStep(const WorldData& d, const StepStatistics& stats) {
  std::string failure = CheckContactGraph(d);
  if (failure.empty()) failure = CheckIslands(d, stats.islands);
  if (failure.empty()) failure = CheckBroadPhase(d, stats.broadPhase.kindUsed);
  return failure;
}

void AbortIfInvalid(const std::string& failure) {
  if (failure.empty()) return;
  std::fprintf(stderr, "talus validation failed: %s\n", failure.c_str());
  std::abort();
}

}  // namespace talus
