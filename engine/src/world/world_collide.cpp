// The collision stage of the step; see world/world_collide.h.
#include "world/world_collide.h"

#include <algorithm>

namespace talus {

void Collide(WorldData& d, StepStatistics& stats) {
  d.previousContacts.swap(d.contacts);
  d.contacts.clear();
  std::sort(d.contacts.begin(), d.contacts.end(),
            [](const Contact& a, const Contact& b) { return a.PairKey() < b.PairKey(); });
  stats.manifolds = static_cast<int>(d.contacts.size());
}

}  // namespace talus
