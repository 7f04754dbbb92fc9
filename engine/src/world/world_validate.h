// The validation pass: checks of the invariants the step's structures
// promise, as Box2D's b2Validate* are. Each check returns an empty string
// when the invariant holds, else a message naming the invariant and the
// ids that break it. Built with TALUS_VALIDATE (CMake option, on in the
// sanitizer tree), World::Step runs CheckStep after every step and
// aborts on a failure (the colouring checks itself where it is made,
// dynamics/constraint_colouring.cpp); without it nothing here runs in a
// step, and the tests call the checks on structures broken by hand.
#pragma once

#include <string>

#include "talus/step_statistics.h"
#include "world/world_data.h"

namespace talus {

/// The contact graph: contacts sorted by pair key with each unordered pair
/// once, each joining two distinct live bodies of which at least one is
/// dynamic, with a point count in range; one anchor record per contact; the
/// SAT caches sorted by pair key, each pair once.
std::string CheckContactGraph(const WorldData& d);

/// Islands and sleep (with WorldSettings::sleeping on, after the sleep
/// pass): two dynamic bodies a contact joins are both awake or both asleep
/// (an island sleeps and wakes whole); a sleeping body has no velocity; the
/// awake islands, recounted here by union-find over the contacts, number
/// `islands` (StepStatistics::islands, the sleep pass's count). Without
/// sleeping no body sleeps.
std::string CheckIslands(const WorldData& d, std::int64_t islands);

/// The broad phase: with the tree used this step (`used`), its parent and
/// child links, heights and boxes (AabbTree::IsValid: each internal box
/// holds its children's, each leaf's holds its proxy's); one proxy per body
/// slot, active exactly for the live bodies with a shape, and finite.
std::string CheckBroadPhase(const WorldData& d, BroadPhaseKind used);

/// Every check above, after a step that returned `stats`.
std::string CheckStep(const WorldData& d, const StepStatistics& stats);

/// Prints "talus validation failed: <failure>" to stderr and aborts when
/// `failure` is not empty.
void AbortIfInvalid(const std::string& failure);

}  // namespace talus
