// The collision stages of the step; see world/world_collide.h.
#include "world/world_collide.h"

#include <algorithm>
#include <span>

#include "collision/collide.h"
#include "collision/manifold_persistence.h"
#include "collision/narrow_phase_scratch.h"
#include "talus/transform.h"

namespace talus {
namespace {

// Items per ParallelFor chunk. A chunk should cost well above the few tens
// of nanoseconds a thread pays to claim it: a proxy is ~20 ns of work, a
// pair's narrow phase a few microseconds (less when its manifold is reused).
// Chunk boundaries depend on these and the item counts only, never on the
// thread count (jobs/job_pool.h).
constexpr int kProxyGrain = 256;
constexpr int kNarrowPhaseGrain = 8;
// A pair's gather is one or two copies of a few hundred bytes.
constexpr int kGatherGrain = 64;

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
// pass). Decided from the bodies as the narrow phase found them, applied
// after it, so that the decision does not depend on pair order or threads.
bool ShouldWake(const BodySim& sleeper, const BodySim& other) {
  return sleeper.type == BodyType::Dynamic && !sleeper.awake && Disturbs(other);
}

void Wake(WorldData& d, std::size_t sleeper) {
  BodySim& body = d.sims[sleeper];
  body.awake = true;
  // It was not integrated this step: it starts it, and keeps, the velocity
  // it has (the solver times bounces from the start velocity).
  body.startLinearVelocity = body.linearVelocity;
  body.freeLinearVelocity = body.linearVelocity;
  d.sleep[sleeper].restTime = 0.0;
}

// Radius of a sphere about the body frame's origin that holds the shape:
// how far a turn of the body can move its farthest point, per radian.
double RadiusAboutOrigin(const Shape& shape) {
  const Sphere& sphere = shape.LocalBoundingSphere();
  return sphere.center.norm() + sphere.radius;
}

// Whether last step's manifold of the pair can be rebuilt from its anchors:
// reuse is on, neither shape is a sphere, the narrow phase recorded the
// manifold, and neither body has moved relative to the other by
// reuseDistance or more since then.
bool CanReuseManifold(const WorldData& d, const ManifoldAnchors& anchors, std::size_t a, std::size_t b,
                      const Transform& xfA, const Transform& xfB) {
  const double reuseDistance = d.settings.methods.narrowPhase.reuseDistance;
  const Shape& shapeA = *d.shapes[a];
  const Shape& shapeB = *d.shapes[b];
  if (!(reuseDistance > 0.0) || !anchors.recorded || shapeA.Type() == ShapeType::Sphere ||
      shapeB.Type() == ShapeType::Sphere) {
    return false;
  }
  const double moved =
      RelativeMotionBound(anchors, xfA, xfB, RadiusAboutOrigin(shapeA), RadiusAboutOrigin(shapeB));
  return moved < reuseDistance;
}

// A kept or rebuilt contact under warm starting keeps its own impulses:
// matched against itself, every point takes its own back (CarryPairImpulses),
// so nothing is copied. Without warm starting a rebuilt one starts from zero,
// as a fresh contact does.
void CarryInPlace(bool warmStarting, Contact& contact) {
  if (warmStarting) {
    contact.persisted = true;
    return;
  }
  contact.normalImpulse.fill(0.0);
  for (Vec3& impulse : contact.frictionImpulse) impulse.setZero();
  contact.persisted = false;
}

// The farthest point of the body's shape from its centre of mass, metres:
// how far a turn moves any of its points, per radian. A constant of the
// body (its shape's bounding sphere and its centre of mass, both in the
// body frame).
double TurningRadius(const Shape& shape, const BodySim& sim) {
  const Sphere& sphere = shape.LocalBoundingSphere();
  return (sphere.center - sim.localCenter).norm() + sphere.radius;
}

// How far the two bodies can close on each other this step
// (MethodSettings::speculativeMotion): the step times the relative speed of
// their centres, as gravity has already left them (IntegrateVelocities ran),
// plus each one's turn rate times its turning radius; a free body moves on
// the mean of its old and new velocity, up to g h / 2 off the new one, so a
// pair with one dynamic body adds g h^2 / 2 (two dynamic bodies fall
// alike). Relative, not each body's own reach: boxes falling side by side
// do not close on each other. The pair's margin is the larger of this and
// the fixed one: a corner that can land within the step is a speculative
// point before it does, and where the reach is below the margin nothing
// changes.
double PairReach(const WorldData& d, const BodySim& simA, const BodySim& simB, std::size_t a, std::size_t b,
                 double h) {
  const bool dynamicA = simA.type == BodyType::Dynamic;
  const bool dynamicB = simB.type == BodyType::Dynamic;
  const double fall = dynamicA != dynamicB ? 0.5 * d.settings.gravity.norm() * h * h : 0.0;
  return h * ((simA.linearVelocity - simB.linearVelocity).norm() +
              simA.angularVelocity.norm() * TurningRadius(*d.shapes[a], simA) +
              simB.angularVelocity.norm() * TurningRadius(*d.shapes[b], simB)) +
         fall;
}

// One pair through the narrow phase: reads the world (bodies, shapes, last
// step's contacts, anchors and caches) and writes only `out` and the pair's
// own entry of last step's contacts (`lastContacts[out.oldContact]`), so
// pairs can run on any thread in any order. `out.oldContact` and
// `out.oldCache` are already set. A Kept or Reused pair's contact stays in
// its entry (a Reused manifold is rebuilt there); a Tested pair's is built
// in `out.contact`, last step's impulses carried into it. `scratch` is the
// running thread's working memory.
void CollidePair(const WorldData& d, std::span<Contact> lastContacts, const BroadPhasePair& pair, double h,
                 NarrowPhaseScratch& scratch, PairOutcome& out) {
  const auto a = static_cast<std::size_t>(pair.a);
  const auto b = static_cast<std::size_t>(pair.b);
  const BodySim& simA = d.sims[a];
  const BodySim& simB = d.sims[b];
  out.touching = false;
  out.wakeA = false;
  out.wakeB = false;
  out.warmStartedPoints = 0;
  const bool warmStarting = d.settings.methods.warmStarting;

  // Nothing on either side can move or disturb the other: keep what was
  // there.
  if (!Disturbs(simA) && !Disturbs(simB)) {
    out.kind = PairOutcome::Kind::Kept;
    if (warmStarting && out.oldContact >= 0)
      lastContacts[static_cast<std::size_t>(out.oldContact)].persisted = true;
    return;
  }

  const Transform xfA = BodyTransform(simA);
  const Transform xfB = BodyTransform(simB);
  const BodyRecord& ra = d.records[a];
  const BodyRecord& rb = d.records[b];
  const double friction = MixFriction(ra.friction, rb.friction, d.settings.frictionCombine);
  const double restitution = MixRestitution(ra.restitution, rb.restitution, d.settings.restitutionCombine);
  const auto markTouching = [&] {
    out.touching = true;
    out.wakeA = ShouldWake(simA, simB);
    out.wakeB = ShouldWake(simB, simA);
  };

  // The pair barely moved since the narrow phase last saw it: rebuild that
  // manifold where it is and keep the anchors (and the SAT cache) as they
  // were, so the reference pose stays the narrow phase's.
  if (out.oldContact >= 0) {
    const auto old = static_cast<std::size_t>(out.oldContact);
    const ManifoldAnchors& anchors = d.contactAnchors[old];
    if (CanReuseManifold(d, anchors, a, b, xfA, xfB)) {
      Contact& contact = lastContacts[old];
      RebuildManifold(anchors, xfA, xfB, &contact.manifold);
      contact.friction = friction;
      contact.restitution = restitution;
      CarryInPlace(warmStarting, contact);
      out.kind = PairOutcome::Kind::Reused;
      markTouching();
      return;
    }
  }
  ContactManifold manifold{};

  out.kind = PairOutcome::Kind::Tested;
  out.stats = NarrowPhaseStats{};
  out.cache = PairSatCache{.pairKey = PairKey(pair.a, pair.b),
                           .cache = out.oldCache >= 0
                                        ? d.previousSatCaches[static_cast<std::size_t>(out.oldCache)].cache
                                        : SatCache{}};
  // A is the lower slot: the manifold's normal points from b towards a.
  out.persistentPoints = 0;
  NarrowPhaseSettings narrow = d.settings.methods.narrowPhase;
  if (d.settings.methods.speculativeMotion) {
    narrow.speculativeMargin = std::max(narrow.speculativeMargin, PairReach(d, simA, simB, a, b, h));
  }
  if (!Collide(*d.shapes[a], xfA, *d.shapes[b], xfB, narrow, &out.cache.cache, &out.stats, &manifold,
               &scratch)) {
    return;
  }
  // Spheres get exact single points from a closed form; only polyhedron
  // pairs remember points, or reuse them (ReuseManifold), so only they need
  // anchors.
  const bool polyhedra = d.shapes[a]->Type() != ShapeType::Sphere && d.shapes[b]->Type() != ShapeType::Sphere;
  const bool persists = narrow.persistence == ManifoldPersistence::Accumulate && polyhedra;
  out.anchors = (narrow.reuseDistance > 0.0 && polyhedra) || persists ? RecordAnchors(manifold, xfA, xfB)
                                                                      : ManifoldAnchors{};
  if (persists) SnapAnchorsToSurfaces(*d.shapes[a], xfA, *d.shapes[b], xfB, manifold, &out.anchors);
  if (persists && out.oldContact >= 0) {
    const auto old = static_cast<std::size_t>(out.oldContact);
    const double breakDistance =
        PersistentBreakDistance(narrow.persistenceDistance, d.shapes[a]->LocalBoundingSphere().radius,
                                d.shapes[b]->LocalBoundingSphere().radius);
    out.persistentPoints =
        MergePersistentPoints(d.contacts[old].manifold, d.contactAnchors[old], xfA, xfB, breakDistance,
                              kPersistentFreshPoints, &manifold, &out.anchors);
  }
  ResetContact(pair.a, pair.b, manifold, friction, restitution, &out.contact);
  markTouching();
  if (warmStarting && out.oldContact >= 0) {
    out.warmStartedPoints =
        CarryPairImpulses(d.contacts[static_cast<std::size_t>(out.oldContact)], out.contact);
  }
}

// Puts one pair's outcome into the places the serial pass of the gather
// gave it (contactSlot, cacheSlot). In place (`inPlace`: every pair's slot
// is its entry of last step) only a tested pair's new contact and anchors
// are written; otherwise the step's lists are built in the spare buffers:
// a kept or reused pair's contact and anchors copied from its entry, a
// tested pair's from its outcome. The SAT caches: a tested pair's new one,
// else last step's.
void GatherPair(WorldData& d, const PairOutcome& outcome, bool inPlace) {
  if (outcome.cacheSlot >= 0) {
    d.satCaches[static_cast<std::size_t>(outcome.cacheSlot)] =
        outcome.kind == PairOutcome::Kind::Tested
            ? outcome.cache
            : d.previousSatCaches[static_cast<std::size_t>(outcome.oldCache)];
  }
  if (outcome.contactSlot < 0) return;
  const auto slot = static_cast<std::size_t>(outcome.contactSlot);
  std::vector<Contact>& contacts = inPlace ? d.contacts : d.spareContacts;
  std::vector<ManifoldAnchors>& anchors = inPlace ? d.contactAnchors : d.spareContactAnchors;
  if (outcome.kind == PairOutcome::Kind::Tested) {
    contacts[slot] = outcome.contact;
    anchors[slot] = outcome.anchors;
    return;
  }
  if (inPlace) return;
  const auto old = static_cast<std::size_t>(outcome.oldContact);
  contacts[slot] = d.contacts[old];
  anchors[slot] = d.contactAnchors[old];
}

// Last step's contact and cache of every pair into its outcome. Pairs come
// sorted by (a, b), which is pair-key order, so one forward walk each finds
// them.
void FindPreviousEntries(WorldData& d) {
  d.pairOutcomes.resize(d.pairs.size());
  std::size_t oldContact = 0;
  std::size_t oldCache = 0;
  for (std::size_t p = 0; p < d.pairs.size(); ++p) {
    const std::uint64_t key = PairKey(d.pairs[p].a, d.pairs[p].b);
    while (oldContact < d.contacts.size() && d.contacts[oldContact].PairKey() < key) ++oldContact;
    while (oldCache < d.previousSatCaches.size() && d.previousSatCaches[oldCache].pairKey < key) ++oldCache;
    PairOutcome& outcome = d.pairOutcomes[p];
    const bool hadContact = oldContact < d.contacts.size() && d.contacts[oldContact].PairKey() == key;
    const bool hadCache =
        oldCache < d.previousSatCaches.size() && d.previousSatCaches[oldCache].pairKey == key;
    outcome.oldContact = hadContact ? static_cast<std::int32_t>(oldContact) : -1;
    outcome.oldCache = hadCache ? static_cast<std::int32_t>(oldCache) : -1;
  }
}

// The narrow phase, each pair into its own slot, on every thread, each
// thread with its own scratch (owned by the pool).
void CollidePairs(WorldData& d, double h) {
  const int pairCount = static_cast<int>(d.pairs.size());
  const std::span<NarrowPhaseScratch> scratch = d.jobs->ThreadScratch<NarrowPhaseScratch>();
  const std::span<Contact> lastContacts(d.contacts);
  d.jobs->ParallelForOnThreads(pairCount, kNarrowPhaseGrain,
                               [&d, h, scratch, lastContacts](int thread, int begin, int end) {
                                 NarrowPhaseScratch& mine = scratch[static_cast<std::size_t>(thread)];
                                 for (int p = begin; p < end; ++p) {
                                   CollidePair(d, lastContacts, d.pairs[static_cast<std::size_t>(p)], h, mine,
                                               d.pairOutcomes[static_cast<std::size_t>(p)]);
                                 }
                               });
}

// The serial half of the gather, in pair order: each pair's places in the
// new lists (contactSlot, cacheSlot), the counts (warm-started points
// included) and the wakes. Returns whether the contacts stay in place:
// every pair with a contact this step has its slot at its entry of last
// step, which holds while no pair begins touching or stops touching before
// the last one (the steady state of a resting or sliding scene). Resizes
// the lists the gather writes to the counts (capacity is kept; GatherPair
// overwrites every element up to the new size that is not already there).
bool AssignGatherSlots(WorldData& d, StepStatistics& stats) {
  const bool warmStarting = d.settings.methods.warmStarting;
  std::int32_t contactCount = 0;
  std::int32_t cacheCount = 0;
  bool inPlace = true;
  std::int64_t warmStarted = 0;
  const auto ownPoints = [&d](const PairOutcome& outcome) {
    return d.contacts[static_cast<std::size_t>(outcome.oldContact)].manifold.pointCount;
  };
  for (std::size_t p = 0; p < d.pairs.size(); ++p) {
    PairOutcome& outcome = d.pairOutcomes[p];
    outcome.contactSlot = -1;
    outcome.cacheSlot = -1;
    switch (outcome.kind) {
      case PairOutcome::Kind::Kept:
        ++stats.sleepingPairsSkipped;
        if (outcome.oldContact >= 0) {
          if (warmStarting) warmStarted += ownPoints(outcome);
          outcome.contactSlot = contactCount++;
          inPlace = inPlace && outcome.contactSlot == outcome.oldContact;
        }
        if (outcome.oldCache >= 0) outcome.cacheSlot = cacheCount++;
        continue;
      case PairOutcome::Kind::Reused:
        ++stats.manifoldsReused;
        stats.reusedContactPoints += ownPoints(outcome);
        if (warmStarting) warmStarted += ownPoints(outcome);
        if (outcome.oldCache >= 0) outcome.cacheSlot = cacheCount++;
        break;
      case PairOutcome::Kind::Tested:
        stats.narrowPhase += outcome.stats;
        stats.persistentPoints += outcome.persistentPoints;
        warmStarted += outcome.warmStartedPoints;
        outcome.cacheSlot = cacheCount++;
        break;
    }
    if (!outcome.touching) continue;
    if (outcome.wakeA) Wake(d, static_cast<std::size_t>(d.pairs[p].a));
    if (outcome.wakeB) Wake(d, static_cast<std::size_t>(d.pairs[p].b));
    outcome.contactSlot = contactCount++;
    inPlace = inPlace && outcome.contactSlot == outcome.oldContact;
  }
  if (warmStarting) stats.warmStartedPoints = warmStarted;
  const auto count = static_cast<std::size_t>(contactCount);
  // In place the list only loses entries past its last contact.
  d.contacts.resize(inPlace ? count : d.contacts.size());
  d.contactAnchors.resize(inPlace ? count : d.contactAnchors.size());
  if (!inPlace) {
    d.spareContacts.resize(count);
    d.spareContactAnchors.resize(count);
  }
  d.satCaches.resize(static_cast<std::size_t>(cacheCount));
  return inPlace;
}

}  // namespace

Result<int> UpdateBroadPhase(WorldData& d, double h) {
  const std::size_t count = d.sims.size();
  // The spheres grow by the speculative margin so pairs that close within
  // the margin reach the narrow phase; with speculativeMotion, by the
  // body's own reach this step where that is larger: |v| + g h (gravity is
  // still to come) plus |w| times its turning radius, so any pair whose
  // PairReach exceeds the margin is found.
  const double margin = d.settings.methods.narrowPhase.speculativeMargin;
  const bool motion = d.settings.methods.speculativeMotion;
  const double gravityStep = d.settings.gravity.norm() * h;
  d.proxies.resize(count);
  d.jobs->ParallelFor(
      static_cast<int>(count), kProxyGrain, [&d, margin, motion, gravityStep, h](int begin, int end) {
        for (auto i = static_cast<std::size_t>(begin); i < static_cast<std::size_t>(end); ++i) {
          BroadPhaseProxy& proxy = d.proxies[i];
          const std::optional<Shape>& shape = d.shapes[i];
          if (!d.records[i].alive || !shape.has_value()) {
            proxy = BroadPhaseProxy{};
            proxy.active = false;
            continue;
          }
          const BodySim& sim = d.sims[i];
          const Sphere& local = shape->LocalBoundingSphere();
          proxy.active = true;
          proxy.sphere.center = BodyTransform(sim).Apply(local.center);
          proxy.sphere.radius = local.radius + margin;
          proxy.isStatic = sim.type != BodyType::Dynamic;
          if (motion) {
            const double speed = sim.linearVelocity.norm() +
                                 sim.angularVelocity.norm() * TurningRadius(*shape, sim) +
                                 (sim.type == BodyType::Dynamic ? gravityStep : 0.0);
            proxy.sphere.radius = local.radius + std::max(margin, speed * h);
          }
        }
      });
  d.broadPhase.SetKind(d.settings.broadPhase);
  d.broadPhase.SetTinyWorldProxies(d.settings.methods.forceBroadPhase ? 0 : kTinyWorldProxies);
  return d.broadPhase.Update(d.proxies);
}

void FindContacts(WorldData& d, double h, StepStatistics& stats) {
  // The swapped-in cache list is resized (not cleared) at the gather, which
  // overwrites every element it keeps. The contacts stay where they are
  // (the store is updated in place, see AssignGatherSlots).
  d.previousSatCaches.swap(d.satCaches);
  d.broadPhase.FindPairs(d.pairs, stats.broadPhase);
  stats.spherePairs = static_cast<std::int64_t>(d.pairs.size());
  stats.staticPairsSkipped = stats.broadPhase.skippedStaticPairs;

  FindPreviousEntries(d);
  CollidePairs(d, h);
  // Gathered in pair order: the contacts stay sorted by pair key and
  // nothing depends on which thread ran which pair. First, serially, each
  // pair's places in the new lists, the counts and the wakes; then the
  // copies (a contact is hundreds of bytes) on every thread, each pair into
  // its own places: in place only the tested pairs' (a kept or reused
  // contact is already in its slot), else every contact into the spare
  // lists, which are then swapped in.
  const bool inPlace = AssignGatherSlots(d, stats);
  d.jobs->ParallelFor(static_cast<int>(d.pairs.size()), kGatherGrain, [&d, inPlace](int begin, int end) {
    for (int p = begin; p < end; ++p) GatherPair(d, d.pairOutcomes[static_cast<std::size_t>(p)], inPlace);
  });
  if (!inPlace) {
    d.contacts.swap(d.spareContacts);
    d.contactAnchors.swap(d.spareContactAnchors);
  }
  stats.manifolds = static_cast<std::int64_t>(d.contacts.size());
}

}  // namespace talus
