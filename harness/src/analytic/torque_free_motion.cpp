// Euler's equations, RK4 and the flip interval (see talus/harness/analytic/torque_free_motion.h).
#include "talus/harness/analytic/torque_free_motion.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <string>

namespace talus::harness {
namespace {

// Steps per turn at the spin rate: RK4's error per step scales as
// (omega dt)^5 ~ (1.5e-3)^5, so over 10^5 steps the flip time is exact to
// far better than the 1e-6 relative the tests ask of it.
constexpr double kStepsPerTurn = 4096.0;
// Steps after which a body that has not flipped twice is given up on.
constexpr long kMaxSteps = 10'000'000;
// Largest angle between omega and the intermediate axis (cos 25 degrees)
// for which "flip" means the turn-over of the body rather than a wobble.
const double kMinAxisAlignment = std::cos(25.0 * std::numbers::pi / 180.0);

}  // namespace

Vec3 EulerEquationsRate(const Vec3& inertia, const Vec3& omega) {
  return Vec3((inertia.y() - inertia.z()) * omega.y() * omega.z() / inertia.x(),
              (inertia.z() - inertia.x()) * omega.z() * omega.x() / inertia.y(),
              (inertia.x() - inertia.y()) * omega.x() * omega.y() / inertia.z());
}

Vec3 EulerEquationsRk4Step(const Vec3& inertia, const Vec3& omega, double dt) {
  const Vec3 k1 = EulerEquationsRate(inertia, omega);
  const Vec3 k2 = EulerEquationsRate(inertia, omega + 0.5 * dt * k1);
  const Vec3 k3 = EulerEquationsRate(inertia, omega + 0.5 * dt * k2);
  const Vec3 k4 = EulerEquationsRate(inertia, omega + dt * k3);
  return omega + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
}

SpinInvariants ComputeSpinInvariants(const Vec3& inertia, const Vec3& omega) {
  const Vec3 momentum = inertia.cwiseProduct(omega);
  return {0.5 * omega.dot(momentum), momentum.norm()};
}

int IntermediateAxis(const Vec3& inertia) {
  const double scale = inertia.cwiseAbs().maxCoeff();
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      if (std::abs(inertia[i] - inertia[j]) <= 1e-9 * scale) return -1;
    }
  }
  for (int i = 0; i < 3; ++i) {
    const double a = inertia[(i + 1) % 3];
    const double b = inertia[(i + 2) % 3];
    if ((inertia[i] - a) * (inertia[i] - b) < 0.0) return i;
  }
  assert(false && "three distinct numbers have a middle one");
  return -1;
}

Result<double> IntermediateAxisFlipInterval(const Vec3& inertia, const Vec3& omega) {
  assert(inertia.minCoeff() > 0.0);
  const int axis = IntermediateAxis(inertia);
  if (axis < 0) return Error{"inertia has no intermediate axis (two principal moments are equal)"};
  const double rate = omega.norm();
  if (!(rate > 0.0) || std::abs(omega[axis]) < kMinAxisAlignment * rate) {
    return Error{"omega is not within 25 degrees of the intermediate axis " + std::to_string(axis)};
  }
  // Integrate until the intermediate component has changed sign twice; the
  // interval between two successive crossings is the same all along the
  // (periodic) motion, while the time to the first depends on the start.
  const double dt = 2.0 * std::numbers::pi / rate / kStepsPerTurn;
  Vec3 w = omega;
  double crossings[2] = {0.0, 0.0};
  int found = 0;
  for (long step = 0; step < kMaxSteps && found < 2; ++step) {
    const Vec3 next = EulerEquationsRk4Step(inertia, w, dt);
    if ((w[axis] > 0.0) != (next[axis] > 0.0)) {
      const double fraction = w[axis] / (w[axis] - next[axis]);
      crossings[found++] = (static_cast<double>(step) + fraction) * dt;
    }
    w = next;
  }
  if (found < 2) return Error{"the body does not turn over within 10^7 integration steps"};
  return crossings[1] - crossings[0];
}

}  // namespace talus::harness
