// The time of impact of a contact point under constant acceleration and the
// reflected flight to the step's end; derivation in dynamics/bounce_timing.h.
#include "dynamics/bounce_timing.h"

#include <algorithm>
#include <cmath>

namespace talus {

TimedBounce TimeBounce(double gap, double speed, double acceleration, double h, double restitution,
                       double threshold) {
  TimedBounce out;
  // Penetrating and already separating: the surface is behind the point.
  if (gap <= 0.0 && speed >= 0.0) return out;
  const double discriminant = speed * speed - 2.0 * acceleration * gap;
  if (!(discriminant > 0.0)) {
    // Apart: the gap never closes. Penetrating: no flight under this
    // acceleration came from outside.
    out.tooDeep = gap <= 0.0;
    return out;
  }
  const double impact = std::sqrt(discriminant);
  double time = 0.0;
  if (speed < 0.0) {
    time = 2.0 * gap / (impact - speed);
  } else if (acceleration < 0.0) {
    time = -(speed + impact) / acceleration;
  } else {
    return out;  // separating and not pulled back
  }
  out.speed = impact;  // also for a landing outside this step (TimedBounce::speed)
  out.tooDeep = time < -h;
  if (!(time >= -h && time <= h) || !(impact > threshold)) return out;
  const double rest = h - time;
  const double rebound = restitution * impact;
  out.hits = true;
  out.time = time;
  out.endSpeed = rebound + acceleration * rest;
  out.endGap = rebound * rest + 0.5 * acceleration * rest * rest;
  if (out.endGap < 0.0) {
    // The rebound comes down again within the step and stays on the
    // surface (bounce_timing.h).
    out.endGap = 0.0;
    out.endSpeed = std::max(out.endSpeed, 0.0);
  }
  return out;
}

}  // namespace talus
