// The pseudo-velocity sweeps of split impulses and timed bounces (see
// dynamics/split_impulses.h).
#include "dynamics/split_impulses.h"

#include <algorithm>

namespace talus {

void SolveSplitImpulses(ContactRowSet& rows, int iterations) {
  for (int it = 0; it < iterations; ++it) {
    for (const PairRows& pair : rows.Pairs()) {
      SolverVelocity& a = rows.Bodies().Pseudo(pair.bodyA);
      SolverVelocity& b = rows.Bodies().Pseudo(pair.bodyB);
      for (int i = 0; i < pair.pointCount; ++i) {
        const std::size_t p = static_cast<std::size_t>(pair.firstPoint + i);
        PointCold& cold = rows.Cold()[p];
        if (!cold.timedBounce && cold.positionTarget <= 0.0 && cold.pseudoImpulse == 0.0) continue;
        const NormalRow& row = rows.Normals()[p];
        const double vn = pair.normal.dot(a.v - b.v) + row.j.angularA.dot(a.w) - row.j.angularB.dot(b.w);
        const double previous = cold.pseudoImpulse;
        // A timed bounce's row is an equality (its end gap, above or below
        // where h times the velocity would put it); the others only push.
        const double next = previous - row.mass * (vn - cold.positionTarget);
        cold.pseudoImpulse = cold.timedBounce ? next : std::max(next, 0.0);
        const double delta = cold.pseudoImpulse - previous;
        const Vec3 impulse = delta * pair.normal;
        a.v += pair.invMassA * impulse;
        a.w += delta * row.j.imageA;
        b.v -= pair.invMassB * impulse;
        b.w -= delta * row.j.imageB;
      }
    }
  }
}

}  // namespace talus
