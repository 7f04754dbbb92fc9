// WorldData: everything a World owns, laid out for the step.
//
// Bodies are structure-of-arrays by concern, all indexed by body index:
// `sims` (hot: what the integrator and solver read), `sleep` (rest timers)
// and `records` (cold: generation, materials, the user's mass data). A
// destroyed body leaves its slot in place with `alive` false and a bumped
// generation; the slot goes on `freeSlots` and is reused last-in first-out,
// so the same sequence of calls always gives the same indices. A dead slot
// is a static body with no contacts, so every stage skips it for free.
//
// `shapes` (cold, by body index) is each body's collision geometry or none.
// The broad phase gets one proxy per slot (inactive for dead or shapeless
// slots). `satCaches` keeps, per tested pair, the SAT's last axis, sorted by
// pair key like the contacts and carried over by the same merge walk.
//
// `jobs` runs the step's parallel loops (settings.threads threads, the
// caller included; see jobs/job_pool.h). It sits behind a pointer so that a
// World stays movable and a thread count can be swapped in whole.
//
// `contacts` holds this step's touching pairs sorted by pair key, with the
// accumulated impulses the solver wrote back; the next step matches against
// it for warm starting. `contactAnchors` runs beside it, one entry per
// contact at the same index: the pair's manifold in the bodies' frames,
// read only by the narrow phase of the same pair next step (manifold reuse,
// persistent points), so the stages that walk the contacts do not drag it
// along (dynamics/contact.h).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "collision/broad_phase.h"
#include "collision/manifold_reuse.h"
#include "collision/sat.h"

#include "dynamics/body_sim.h"
#include "dynamics/contact.h"
#include "dynamics/contact_solver.h"
#include "dynamics/sleep.h"
#include "dynamics/soft_step_solver.h"
#include "jobs/job_pool.h"
#include "talus/body.h"
#include "talus/shape.h"
#include "talus/world_settings.h"

namespace talus {

/// Cold per-body data.
struct BodyRecord {
  std::uint32_t generation = 0;
  bool alive = false;
  double friction = 0.0;
  double restitution = 0.0;
  double mass = 0.0;                 ///< kg as given (0 unless dynamic)
  Mat3 localInertia = Mat3::Zero();  ///< kg m^2 as given (0 unless dynamic)
};

/// The SAT's temporal-coherence cache of one tested pair.
struct PairSatCache {
  std::uint64_t pairKey = 0;
  SatCache cache;
};
// The narrow phase's per-pair cache entry, one per tested pair, searched by
// key and copied at every gather (docs/collision-narrow-phase.md, Record
// sizes).
static_assert(sizeof(PairSatCache) == 40, "PairSatCache: pair key and a 32-byte SatCache");

/// What the narrow phase made of one broad-phase pair this step. Written by
/// whichever thread ran the pair, read back in pair order, so the contacts
/// come out in the same order whatever the thread count.
//
// The anchors lead (under AVX Eigen aligns their quaternion to 32 bytes,
// and behind the 20 bytes of flags and indices they were padded to 1,312).
struct PairOutcome {
  /// Tested and touching: the new manifold's anchors (Kept and Reused pairs
  /// keep theirs where they are in WorldData::contactAnchors).
  ManifoldAnchors anchors;
  /// Tested and touching: this step's contact, last step's impulses carried
  /// over (Kept and Reused pairs keep theirs in WorldData::contacts, where
  /// a Reused pair's manifold is rebuilt in place).
  Contact contact;
  PairSatCache cache;      ///< Tested: the pair's new SAT cache
  NarrowPhaseStats stats;  ///< Tested: the narrow phase's counts for this pair
  enum class Kind : std::uint8_t {
    Kept,    ///< nothing on either side disturbs the other: last step's contact and cache stand
    Reused,  ///< manifold rebuilt from last step's anchors; last step's cache stands
    Tested,  ///< the narrow phase ran; `cache` is its new SAT cache
  };
  Kind kind = Kind::Tested;
  bool touching = false;               ///< Reused or Tested: the pair has a contact this step
  bool wakeA = false;                  ///< touching, and body a sleeps while b disturbs it
  bool wakeB = false;                  ///< the same for body b
  std::int32_t oldContact = -1;        ///< index of last step's contact of the pair, or -1
  std::int32_t oldCache = -1;          ///< index of last step's SAT cache of the pair, or -1
  std::int32_t contactSlot = -1;       ///< the gather's: index in this step's contacts, or -1
  std::int32_t cacheSlot = -1;         ///< the gather's: index in this step's SAT caches, or -1
  std::int32_t persistentPoints = 0;   ///< Tested: last step's points merged back (manifold_persistence.h)
  std::int32_t warmStartedPoints = 0;  ///< Tested: points that found last step's impulses (CarryPairImpulses)
};
// One per broad-phase pair every step, written by a worker and read by the
// gather: mostly the Contact and ManifoldAnchors budgeted in
// dynamics/contact.h (docs/collision-narrow-phase.md, Record sizes).
static_assert(sizeof(PairOutcome) <= 1280, "PairOutcome grew past its 1,280-byte budget");

struct WorldData {
  WorldSettings settings;
  std::vector<BodySim> sims;
  std::vector<SleepState> sleep;
  std::vector<BodyRecord> records;
  std::vector<std::int32_t> freeSlots;
  std::vector<std::optional<Shape>> shapes;
  int liveBodies = 0;

  BroadPhase broadPhase;
  std::vector<BroadPhaseProxy> proxies;
  std::vector<BroadPhasePair> pairs;
  std::vector<PairSatCache> satCaches;
  std::vector<PairSatCache> previousSatCaches;

  /// The persistent contact store (world/world_collide.h): one contact per
  /// touching pair, sorted by pair key, updated in place while the pair set
  /// holds its order.
  std::vector<Contact> contacts;
  /// Each contact's manifold in its bodies' frames, same index as `contacts`.
  std::vector<ManifoldAnchors> contactAnchors;
  /// The gather's other buffers, used only in a step whose pairs moved in
  /// the list (some pair began or stopped touching): the step's contacts
  /// are built there and swapped in. Kept for their capacity; between steps
  /// they hold nothing anyone reads.
  std::vector<Contact> spareContacts;
  std::vector<ManifoldAnchors> spareContactAnchors;
  ContactSolver solver;
  SoftStepSolver softSolver;  ///< MethodSettings::stepSolver = SoftStep
  SleepManager sleepManager;

  /// The step's threads, settings.threads of them (no worker for 1).
  std::unique_ptr<JobPool> jobs = std::make_unique<JobPool>(1);
  /// The narrow phase's per-pair results of this step, in pair order
  /// (world/world_collide.cpp); kept for their capacity.
  std::vector<PairOutcome> pairOutcomes;
};

}  // namespace talus
