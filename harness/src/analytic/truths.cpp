// Closed-form ground truths (see talus/harness/analytic/truths.h).
#include "talus/harness/analytic/truths.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace talus::harness {

double FreeFallHeight(double y0, double v0, double g, double t) { return y0 + v0 * t - 0.5 * g * t * t; }

double FreeFallHeightSymplecticEuler(double y0, double v0, double g, double h, int n) {
  assert(h > 0.0 && n >= 0);
  const double t = h * n;
  return y0 + v0 * t - 0.5 * g * t * t - 0.5 * g * h * t;
}

double FreeFallHeightExplicitEuler(double y0, double v0, double g, double h, int n) {
  assert(h > 0.0 && n >= 0);
  const double t = h * n;
  return y0 + v0 * t - 0.5 * g * t * t + 0.5 * g * h * t;
}

double SlidingStopDistance(double v0, double mu, double g) {
  assert(mu > 0.0 && g > 0.0);
  return v0 * v0 / (2.0 * mu * g);
}

double SlidingStopDistanceSymplecticEuler(double v0, double mu, double g, double h) {
  assert(mu > 0.0 && g > 0.0 && h > 0.0 && v0 >= 0.0);
  // Speeds v_k = v0 - k a h stay positive for k < v0 / (a h); the step that
  // would reverse the motion is clamped to rest and moves nothing.
  const double a = mu * g;
  const long steps = static_cast<long>(std::floor(v0 / (a * h)));
  double distance = 0.0;
  for (long k = 1; k <= steps; ++k) distance += h * std::max(0.0, v0 - static_cast<double>(k) * a * h);
  return distance;
}

double SlidingStopTime(double v0, double mu, double g) {
  assert(mu > 0.0 && g > 0.0);
  return v0 / (mu * g);
}

double SlidingStopTimeSymplecticEuler(double v0, double mu, double g, double h) {
  assert(mu > 0.0 && g > 0.0 && h > 0.0 && v0 >= 0.0);
  return std::ceil(v0 / (mu * g * h)) * h;
}

double SlidingSlowTime(double v0, double mu, double g, double speed) {
  assert(mu > 0.0 && g > 0.0 && speed >= 0.0);
  return std::max(v0 - speed, 0.0) / (mu * g);
}

double SlidingSlowTimeSymplecticEuler(double v0, double mu, double g, double h, double speed) {
  assert(mu > 0.0 && g > 0.0 && h > 0.0 && v0 >= 0.0 && speed > 0.0);
  if (v0 < speed) return 0.0;
  // The first k with v0 - k mu g h < speed (the clamp at zero only matters
  // once the speed is already below any positive threshold).
  return (std::floor((v0 - speed) / (mu * g * h)) + 1.0) * h;
}

double StackRestHeight(double floor, double layerHeight, int layer) {
  assert(layer >= 0);
  return floor + (layer + 0.5) * layerHeight;
}

double InclineAcceleration(double angle, double mu, double g) {
  assert(angle >= 0.0 && angle < 0.5 * std::numbers::pi && mu >= 0.0 && g > 0.0);
  if (std::tan(angle) <= mu) return 0.0;
  return g * (std::sin(angle) - mu * std::cos(angle));
}

double InclineDistance(double angle, double mu, double g, double t) {
  return 0.5 * InclineAcceleration(angle, mu, g) * t * t;
}

double InclineDistanceSymplecticEuler(double angle, double mu, double g, double h, int n) {
  assert(h > 0.0 && n >= 0);
  const double steps = static_cast<double>(n);
  return 0.5 * InclineAcceleration(angle, mu, g) * h * h * steps * (steps + 1.0);
}

InclineOutcome InclineBoxOutcome(double angle, double mu, double width, double height) {
  assert(width > 0.0 && height > 0.0);
  const double slope = std::tan(angle);
  const double aspect = width / height;
  if (slope <= mu) return slope > aspect ? InclineOutcome::Tips : InclineOutcome::Stays;
  return mu > aspect ? InclineOutcome::Tips : InclineOutcome::Slides;
}

const char* InclineOutcomeName(InclineOutcome outcome) {
  switch (outcome) {
    case InclineOutcome::Stays:
      return "stays";
    case InclineOutcome::Slides:
      return "slides";
    case InclineOutcome::Tips:
      return "tips";
  }
  assert(false && "unknown incline outcome");
  return "";
}

std::vector<double> BounceApexHeights(double h, double e, int count) {
  assert(count >= 0);
  std::vector<double> heights;
  double height = h;
  for (int k = 0; k < count; ++k) {
    height *= e * e;
    heights.push_back(height);
  }
  return heights;
}

}  // namespace talus::harness
