// Sleeping: islands of dynamic bodies at rest stop costing time.
//
// An island is a set of dynamic bodies connected through contacts (static
// and kinematic bodies do not join islands: a floor under a thousand boxes
// must not weld them into one island). Every awake dynamic body keeps a rest
// timer that grows while its linear and angular speeds stay under the
// thresholds and resets otherwise. After each step the islands are rebuilt
// with a union-find over this step's contacts (union by smaller index, so
// the result does not depend on contact order); an island whose every body
// has rested for timeToSleep falls asleep (velocities zeroed, no longer
// integrated or solved); an island holding any body that has not rested
// that long is woken whole. A body woken by a force or a user call has its
// timer reset, which wakes its island on the next pass; a moving body that
// touches a sleeping one joins its island and wakes it the same way.
#pragma once

#include <span>
#include <vector>

#include "dynamics/body_sim.h"
#include "dynamics/contact.h"
#include "talus/world_settings.h"

namespace talus {

/// Per-body sleep bookkeeping, cold data kept beside the BodySim array.
struct SleepState {
  double restTime = 0.0;   ///< seconds the body has been at rest
  bool allowSleep = true;  ///< the body's own permission (BodyDef::allowSleep)
};

class SleepManager {
 public:
  /// Advances rest timers by `h` seconds, builds islands from `contacts` and
  /// puts to sleep or wakes whole islands. `bodies` and `states` are indexed
  /// alike. Returns the number of islands with awake bodies.
  int Update(std::span<BodySim> bodies, std::span<SleepState> states, std::span<const Contact> contacts,
             const WorldSettings& settings, double h);

 private:
  int Find(int body);
  void Union(int a, int b);

  std::vector<int> m_parent;            ///< union-find forest, by body index
  std::vector<double> m_islandMinRest;  ///< per root: smallest rest time in the island
};

}  // namespace talus
