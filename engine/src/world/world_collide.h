// The World's collision stages: from body states to this step's persistent
// contacts (section 2 of the write-up: broad phase, then narrow phase).
//
// UpdateBroadPhase hands the broad phase one bounding sphere per body slot
// (dead and shapeless slots inactive; static and kinematic bodies marked
// static, so pairs of two bodies that cannot be pushed are never found). It
// runs before anything else in the step and is the one stage that can
// refuse (a body beyond the broad phase's coordinate range), so a refusal
// leaves the world unchanged.
//
// FindContacts updates the persistent contact store, `contacts` (with its
// anchors beside it), to one Contact per touching pair, in the broad
// phase's (a, b) order, which is pair-key order, last step's impulses
// carried into each (warm starting: CarryPairImpulses). The store is updated
// in place: a pair whose manifold is kept or rebuilt stays in its entry with
// its impulses (matched against itself, a manifold takes every point's own
// impulses back, so nothing needs copying), and only a tested pair's new
// record is written, into its entry. In a step where some pair begins or
// stops touching before the last one, the entries move, and the step's
// list is built in the spare buffers and swapped in. Pairs whose bodies
// are all asleep (or asleep against static or kinematic) skip the narrow
// phase and keep last step's contact, so a sleeping island stays connected
// and costs nothing. A polyhedron pair that barely moved relative to the
// pose at which the narrow phase last computed its manifold (less than
// NarrowPhaseSettings::reuseDistance) skips the narrow phase too: its
// manifold is rebuilt from the anchors kept beside its Contact
// (WorldData::contactAnchors, collision/manifold_reuse.h), and its SAT cache
// is kept as it was.
//
// Threads (WorldSettings::threads): the proxies are computed per body and
// the narrow phase per pair on the world's JobPool. Each pair writes its own
// PairOutcome slot and reads only what no other pair writes (the bodies,
// shapes, last step's contacts and caches); the slots are then gathered in
// pair order. So every decision, the skips and the waking of a sleeping
// body touched by a disturbing one included, is taken from the bodies as
// the narrow phase found them, and the contacts, caches and counts are the
// same bits for any thread count. The broad phase's pair search itself runs
// on the calling thread (1-2% of a step).
#pragma once

#include "talus/result.h"
#include "talus/step_statistics.h"
#include "world/world_data.h"

namespace talus {

/// Feeds the broad phase this step's bounding spheres, each grown by the
/// speculative margin or, with MethodSettings::speculativeMotion, by its
/// body's reach over the step of `h` seconds where that is larger; an
/// Error (nothing changed) when a body left the broad phase's valid range.
Result<int> UpdateBroadPhase(WorldData& d, double h);

/// Rebuilds `d.contacts` from the broad phase's pairs and the narrow phase
/// (with speculativeMotion, each pair's margin from its reach over the step
/// of `h` seconds); adds its counts to `stats`.
void FindContacts(WorldData& d, double h, StepStatistics& stats);

}  // namespace talus
