// Ground truths in closed form: the continuous-time answer of the physics,
// and, where an engine integrates with symplectic Euler (v += h a; x += h v),
// the exact answer of that integrator, so that a check can tell integrator
// error (which the second removes) from solver error (which it does not).
#pragma once

#include <vector>

namespace talus::harness {

/// Height at time t (s) of a body thrown up at v0 (m/s) from y0 (m) under
/// gravity g (m/s^2, > 0): y0 + v0 t - g t^2 / 2.
double FreeFallHeight(double y0, double v0, double g, double t);

/// The same after n symplectic Euler steps of h seconds. With t = n h,
/// v_k = v0 - k g h and y_n = y0 + h sum v_k = y0 + v0 t - g t^2/2 - g h t/2:
/// the integrator lags the parabola by g h t / 2.
double FreeFallHeightSymplecticEuler(double y0, double v0, double g, double h, int n);

/// The same after n explicit (forward) Euler steps (x += h v; v += h a):
/// y_n = y0 + v0 t - g t^2/2 + g h t/2, ahead of the parabola by g h t / 2.
/// The parabola itself is what any scheme exact for a constant force gives
/// (velocity Verlet, RK4, Talus's ExactConstantAcceleration).
double FreeFallHeightExplicitEuler(double y0, double v0, double g, double h, int n);

/// Distance (m) a body sliding at v0 (m/s) covers before friction mu (> 0)
/// under gravity g stops it: v0^2 / (2 mu g).
double SlidingStopDistance(double v0, double mu, double g);

/// The same for symplectic Euler steps of h seconds when the solver removes
/// exactly mu g h of speed per step and clamps at zero: h sum_k max(0, v0 - k mu g h).
double SlidingStopDistanceSymplecticEuler(double v0, double mu, double g, double h);

/// Time (s) the same slide lasts: v0 / (mu g).
double SlidingStopTime(double v0, double mu, double g);

/// The same for symplectic Euler steps of h seconds under the clamped
/// solver above: the first step whose speed reaches zero, ceil(v0 / (mu g h)) h.
double SlidingStopTimeSymplecticEuler(double v0, double mu, double g, double h);

/// Time (s) until the same slide's speed first falls below `speed` (m/s,
/// >= 0): (v0 - speed) / (mu g), zero when it starts below; `speed` 0 is
/// SlidingStopTime.
double SlidingSlowTime(double v0, double mu, double g, double speed);

/// The same for symplectic Euler steps of h seconds under the clamped
/// solver: the first step k h whose speed max(0, v0 - k mu g h) is below
/// `speed` (> 0). A stop seen by a speed threshold is compared with this,
/// like for like: at small steps the threshold is crossed several steps
/// before the speed reaches zero (1 cm/s is 2 steps at 1/480 s, mu 0.3).
double SlidingSlowTimeSymplecticEuler(double v0, double mu, double g, double h, double speed);

/// Rest height (m, of the centre of mass along the up axis) of a box in layer
/// `layer` (0 = on the floor) of a stack of boxes each `layerHeight` metres
/// tall standing on a floor whose top is at `floor`: floor + (layer + 1/2)
/// layerHeight. Rigid contact: integrator and continuous answers agree.
double StackRestHeight(double floor, double layerHeight, int layer);

/// Acceleration (m/s^2) along an incline of `angle` radians (in [0, pi/2))
/// of a block with friction mu under gravity g: g (sin angle - mu cos angle)
/// when tan(angle) > mu, else 0 (static friction holds it).
double InclineAcceleration(double angle, double mu, double g);

/// Distance (m) slid along that incline after t seconds from rest: a t^2 / 2.
double InclineDistance(double angle, double mu, double g, double t);

/// The same after n symplectic Euler steps of h seconds: v_k = k a h and
/// x_n = h sum_{k=1..n} v_k = a h^2 n (n + 1) / 2 = a t^2 / 2 + a h t / 2.
double InclineDistanceSymplecticEuler(double angle, double mu, double g, double h, int n);

/// What a box standing on an incline does.
enum class InclineOutcome {
  Stays,   ///< static friction holds it and the weight's line stays inside the base
  Slides,  ///< it slides without turning over
  Tips,    ///< it turns over its downhill edge
};

/// The outcome for a box of base `width` (m, along the slope) and `height`
/// (m, along the slope normal), friction mu, on an incline of `angle` rad.
/// Moment balance about the centre of mass puts the normal force's centre
/// at (h/2) f/N from the middle of the base, where f/N is tan(angle) while
/// it holds and mu while it slides; the box tips when that passes the
/// downhill edge (w/2): held, when tan(angle) > w/h; sliding, when mu > w/h.
InclineOutcome InclineBoxOutcome(double angle, double mu, double width, double height);

/// "stays", "slides" or "tips".
const char* InclineOutcomeName(InclineOutcome outcome);

/// Apex heights after each of the first `count` bounces of a body dropped
/// from h metres (its lowest point above the floor) with restitution e:
/// e^2 h, e^4 h, ... (velocity after bounce k is e^k times the impact speed).
std::vector<double> BounceApexHeights(double h, double e, int count);

}  // namespace talus::harness
