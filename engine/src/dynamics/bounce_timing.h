// Bounce timing: where inside a step a contact point reaches the surface and
// where the reflected flight leaves it at the step's end
// (MethodSettings::bounceTiming = TimeOfImpact).
//
// Along the contact normal the point's gap (metres, > 0 apart) moves, while
// nothing touches it, as
//   g(t) = g0 + u0 t + a t^2 / 2,
// u0 the normal speed at the step's start (< 0 closing) and a the normal
// acceleration forces give the pair (gravity's difference; -g for a ball
// over a static floor). The point reaches the surface where g falls through
// zero: of the two roots (-u0 -+ sqrt(D)) / a, D = u0^2 - 2 a g0, the one
// with g' = -sqrt(D) < 0. Its impact speed is therefore sqrt(D) (energy:
// u*^2 = u0^2 - 2 a g0), and its time, written without cancellation,
//   t* = 2 g0 / (sqrt(D) - u0)   when u0 < 0,
//   t* = -(u0 + sqrt(D)) / a     when u0 >= 0 (a < 0 brings it back).
// t* is in [0, h] for a speculative point that hits this step, in [-h, 0]
// for a point the last step carried through the surface (the impact was
// then in the past; the flight since is undone, as the reflected flight
// starts at t*).
//
// The bounce reflects the impact speed, u+ = e sqrt(D), and flies the rest
// of the step, r = h - t* (in [0, 2h]):
//   end normal speed  u(h) = u+ + a r,
//   end gap           g(h) = u+ r + a r^2 / 2.
// A rebound so slow that it would come down again within the step (g(h) <
// 0) ends on the surface, g(h) = 0, its speed u(h) no lower than 0: it
// lands at its rebound speed e sqrt(D), which a second bounce would need
// above the threshold too (it rarely is: e sqrt(D) < -a r / 2 <= g h).
// The contact solver asks the velocity row for u(h) and moves the point
// onto g(h) with a position (pseudo-velocity) row: a velocity times h cannot
// place it there, as the impact splits the step into two flights.
#pragma once

namespace talus {

/// A contact point's impact inside (or just before) a step, when there is one.
struct TimedBounce {
  bool hits = false;  ///< the point reaches the surface at t* in [-h, h], faster than the threshold
  double time = 0.0;  ///< t*, seconds from the step's start (< 0: the last step carried it through)
  /// Impact speed sqrt(D), m/s, > 0, whenever this flight crosses the
  /// surface, also outside [-h, h] (a later landing: the caller can tell
  /// whether it will bounce); 0 when it never does.
  double speed = 0.0;
  double endSpeed = 0.0;  ///< normal speed at the step's end after the bounce, m/s
  double endGap = 0.0;    ///< gap at the step's end after the bounce, metres, >= 0
  /// Penetrating deeper than one step of approach explains (t* < -h, or no
  /// flight under this acceleration crosses the surface): not a bounce this
  /// scheme can time (the caller falls back to the step's boundary).
  bool tooDeep = false;
};

/// The bounce of a point with gap `gap` (metres; < 0 penetrating), normal
/// speed `speed` at the step's start (m/s, < 0 closing) and normal
/// acceleration `acceleration` (m/s^2) over a step of `h` seconds with
/// restitution `restitution` in (0, 1]: `hits` is false when the point does
/// not reach the surface in [-h, h] (`tooDeep` when t* < -h), when it is
/// penetrating and already separating, or when its impact speed is at most
/// `threshold` (m/s).
TimedBounce TimeBounce(double gap, double speed, double acceleration, double h, double restitution,
                       double threshold);

}  // namespace talus
