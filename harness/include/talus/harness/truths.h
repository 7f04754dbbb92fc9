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

/// Distance (m) a body sliding at v0 (m/s) covers before friction mu (> 0)
/// under gravity g stops it: v0^2 / (2 mu g).
double SlidingStopDistance(double v0, double mu, double g);

/// The same for symplectic Euler steps of h seconds when the solver removes
/// exactly mu g h of speed per step and clamps at zero: h sum_k max(0, v0 - k mu g h).
double SlidingStopDistanceSymplecticEuler(double v0, double mu, double g, double h);

/// Apex heights after each of the first `count` bounces of a body dropped
/// from h metres (its lowest point above the floor) with restitution e:
/// e^2 h, e^4 h, ... (velocity after bounce k is e^k times the impact speed).
std::vector<double> BounceApexHeights(double h, double e, int count);

}  // namespace talus::harness
