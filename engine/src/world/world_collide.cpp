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

// Whether the body can disturb what it touches this step: an awake dynamic
// body, or a kinematic body that is moving.
bool Disturbs(const BodySim& sim) {
  if (sim.type == BodyType::Kinematic) return sim.linearVelocity.any() || sim.angularVelocity.any();
  return sim.IsSolverDynamic();
}

// A sleeping dynamic body touched by something that disturbs it wakes now,
// so this step's solve already pushes it (its island follows at the sleep
// pass).
void WakeIfTouched(WorldData& d, std::size_t sleeper, const BodySim& other) {
  BodySim& sim = d.sims[sleeper];
  if (sim.type != BodyType::Dynamic || sim.awake || !Disturbs(other)) return;
  sim.awake = true;
  d.sleep[sleeper].restTime = 0.0;
}

// Radius of a sphere about the body frame's origin that holds the shape:
// how far a turn of the body can move its farthest point, per radian.
double RadiusAboutOrigin(const Shape& shape) {
  const Sphere& sphere = shape.LocalBoundingSphere();
  return sphere.center.norm() + sphere.radius;
}

// Rebuilds last step's manifold of the pair from its anchors when reuse is
// on, neither shape is a sphere, the narrow phase recorded the manifold,
// and neither body has moved relative to the other by reuseDistance or more
// since then. Returns false (nothing written) otherwise.
bool ReuseManifold(const WorldData& d, const Contact& before, std::size_t a, std::size_t b,
                   const Transform& xfA, const Transform& xfB, ContactManifold* manifold) {
  const double reuseDistance = d.settings.narrowPhase.reuseDistance;
  const Shape& shapeA = *d.shapes[a];
  const Shape& shapeB = *d.shapes[b];
  if (!(reuseDistance > 0.0) || !before.anchors.recorded || shapeA.Type() == ShapeType::Sphere ||
      shapeB.Type() == ShapeType::Sphere) {
    return false;
  }
  const double moved =
      RelativeMotionBound(before.anchors, xfA, xfB, RadiusAboutOrigin(shapeA), RadiusAboutOrigin(shapeB));
  if (!(moved < reuseDistance)) return false;
  *manifold = before.manifold;
  RebuildManifold(before.anchors, xfA, xfB, manifold);
  return true;
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
  d.broadPhase.SetTinyWorldProxies(d.settings.forceBroadPhase ? 0 : kTinyWorldProxies);
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

    // Nothing on either side can move or disturb the other: keep what was
    // there.
    if (!Disturbs(simA) && !Disturbs(simB)) {
      ++stats.sleepingPairsSkipped;
      if (hadContact) d.contacts.push_back(d.previousContacts[oldContact]);
      if (hadCache) d.satCaches.push_back(d.previousSatCaches[oldCache]);
      continue;
    }

    const Transform xfA = BodyTransform(simA);
    const Transform xfB = BodyTransform(simB);
    const BodyRecord& ra = d.records[a];
    const BodyRecord& rb = d.records[b];
    const auto addContact = [&](const ContactManifold& manifold, const ManifoldAnchors& anchors) {
      WakeIfTouched(d, a, simB);
      WakeIfTouched(d, b, simA);
      d.contacts.push_back(MakeContact(
          pair.a, pair.b, manifold, MixFriction(ra.friction, rb.friction, d.settings.frictionCombine),
          MixRestitution(ra.restitution, rb.restitution, d.settings.restitutionCombine)));
      d.contacts.back().anchors = anchors;
    };
    ContactManifold manifold{};

    // The pair barely moved since the narrow phase last saw it: rebuild
    // that manifold and keep the anchors (and the SAT cache) as they were,
    // so the reference pose stays the narrow phase's.
    if (hadContact && ReuseManifold(d, d.previousContacts[oldContact], a, b, xfA, xfB, &manifold)) {
      addContact(manifold, d.previousContacts[oldContact].anchors);
      if (hadCache) d.satCaches.push_back(d.previousSatCaches[oldCache]);
      ++stats.manifoldsReused;
      stats.reusedContactPoints += manifold.pointCount;
      continue;
    }

    PairSatCache cache{.pairKey = key, .cache = hadCache ? d.previousSatCaches[oldCache].cache : SatCache{}};
    // A is the lower slot: the manifold's normal points from b towards a.
    if (Collide(*d.shapes[a], xfA, *d.shapes[b], xfB, d.settings.narrowPhase, &cache.cache,
                &stats.narrowPhase, &manifold)) {
      addContact(manifold, d.settings.narrowPhase.reuseDistance > 0.0 ? RecordAnchors(manifold, xfA, xfB)
                                                                      : ManifoldAnchors{});
    }
    d.satCaches.push_back(cache);
  }
  stats.manifolds = static_cast<std::int32_t>(d.contacts.size());
}

}  // namespace talus
