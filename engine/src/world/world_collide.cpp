// The collision stages of the step; see world/world_collide.h.
#include "world/world_collide.h"

#include <algorithm>

#include "collision/collide.h"
#include "talus/transform.h"

namespace talus {
namespace {

std::uint64_t PairKeyOf(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

Transform BodyTransform(const BodySim& sim) {
  return {.position = sim.Origin(), .rotation = sim.orientation};
}

}  // namespace

Result<int> UpdateBroadPhase(WorldData& d) {
  const std::size_t count = d.sims.size();
  // The spheres grow by the speculative margin so pairs that close within
  // the margin reach the narrow phase.
  const double margin = d.settings.narrowPhase.speculativeMargin;
  d.proxies.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    BroadPhaseProxy& proxy = d.proxies[i];
    const std::optional<Shape>& shape = d.shapes[i];
    proxy.active = d.records[i].alive && shape.has_value();
    if (!proxy.active) {
      proxy = BroadPhaseProxy{};
      proxy.active = false;
      continue;
    }
    const BodySim& sim = d.sims[i];
    const Sphere& local = shape->LocalBoundingSphere();
    proxy.sphere.center = BodyTransform(sim).Apply(local.center);
    proxy.sphere.radius = local.radius + margin;
    proxy.isStatic = sim.type != BodyType::Dynamic;
  }
  d.broadPhase.SetKind(d.settings.broadPhase);
  return d.broadPhase.Update(d.proxies);
}

void FindContacts(WorldData& d, StepStatistics& stats) {
  d.previousContacts.swap(d.contacts);
  d.contacts.clear();
  d.previousSatCaches.swap(d.satCaches);
  d.satCaches.clear();
  d.broadPhase.FindPairs(d.pairs, stats.broadPhase);
  stats.candidatePairs = static_cast<std::int32_t>(d.pairs.size());
  stats.staticPairsSkipped = static_cast<std::int32_t>(stats.broadPhase.skippedStaticPairs);

  // Pairs come sorted by (a, b), which is pair-key order, so last step's
  // contacts and caches are found by one forward walk each.
  std::size_t oldContact = 0;
  std::size_t oldCache = 0;
  for (const BroadPhasePair& pair : d.pairs) {
    const std::uint64_t key = PairKeyOf(pair.a, pair.b);
    while (oldContact < d.previousContacts.size() && d.previousContacts[oldContact].PairKey() < key)
      ++oldContact;
    while (oldCache < d.previousSatCaches.size() && d.previousSatCaches[oldCache].pairKey < key) ++oldCache;
    const bool hadContact =
        oldContact < d.previousContacts.size() && d.previousContacts[oldContact].PairKey() == key;
    const bool hadCache =
        oldCache < d.previousSatCaches.size() && d.previousSatCaches[oldCache].pairKey == key;
    const std::size_t a = static_cast<std::size_t>(pair.a);
    const std::size_t b = static_cast<std::size_t>(pair.b);
    const BodySim& simA = d.sims[a];
    const BodySim& simB = d.sims[b];

    // Nothing on either side can move: keep what was there.
    if (!simA.IsSolverDynamic() && !simB.IsSolverDynamic()) {
      ++stats.sleepingPairsSkipped;
      if (hadContact) d.contacts.push_back(d.previousContacts[oldContact]);
      if (hadCache) d.satCaches.push_back(d.previousSatCaches[oldCache]);
      continue;
    }

    PairSatCache cache{.pairKey = key, .cache = hadCache ? d.previousSatCaches[oldCache].cache : SatCache{}};
    ContactManifold manifold{};
    // A is the lower slot: the manifold's normal points from b towards a.
    if (Collide(*d.shapes[a], BodyTransform(simA), *d.shapes[b], BodyTransform(simB), d.settings.narrowPhase,
                &cache.cache, &stats.narrowPhase, &manifold)) {
      const BodyRecord& ra = d.records[a];
      const BodyRecord& rb = d.records[b];
      d.contacts.push_back(MakeContact(
          pair.a, pair.b, manifold, MixFriction(ra.friction, rb.friction, d.settings.frictionCombine),
          MixRestitution(ra.restitution, rb.restitution, d.settings.restitutionCombine)));
    }
    d.satCaches.push_back(cache);
  }
  stats.manifolds = static_cast<std::int32_t>(d.contacts.size());
}

}  // namespace talus
