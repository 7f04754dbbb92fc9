// The World's collision stage: from body states to this step's persistent
// contacts.
//
// Collide moves last step's contacts to `previousContacts` (for warm
// starting) and fills `contacts` with one Contact per touching pair, sorted
// by pair key, materials mixed by the settings' combine rules. Pairs of two
// bodies that cannot move (static or kinematic against static or
// kinematic) are never tested; pairs whose bodies are all asleep or static
// keep last step's contact unchanged without a narrow-phase test, so a
// sleeping island stays connected and costs nothing.
#pragma once

#include "talus/step_statistics.h"
#include "world/world_data.h"

namespace talus {

/// Rebuilds `d.contacts` for the current body positions; adds its counts to
/// `stats`.
void Collide(WorldData& d, StepStatistics& stats);

}  // namespace talus
