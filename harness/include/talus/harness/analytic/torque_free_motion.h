// Torque-free rigid rotation: Euler's equations in the body's principal
// frame, their invariants, and the period with which a body spun about its
// intermediate axis turns over (the Dzhanibekov or tennis-racket effect).
//
// The flip interval is found by integrating Euler's equations with the
// classical fourth-order Runge-Kutta method at a small step (a few thousand
// steps per turn), not from the closed form in Jacobi elliptic functions;
// the tests check the integration against that closed form
// (Landau and Lifshitz, Mechanics, section 37), so each is an independent
// check of the other.
#pragma once

#include "talus/math.h"
#include "talus/result.h"

namespace talus::harness {

/// d(omega)/dt of a torque-free body with principal moments `inertia`
/// (kg m^2, each > 0) at body-frame angular velocity `omega` (rad/s):
/// I1 w1' = (I2 - I3) w2 w3, and cyclically.
Vec3 EulerEquationsRate(const Vec3& inertia, const Vec3& omega);

/// One classical Runge-Kutta (RK4) step of `dt` seconds of those equations.
Vec3 EulerEquationsRk4Step(const Vec3& inertia, const Vec3& omega, double dt);

/// The two invariants of torque-free motion.
struct SpinInvariants {
  double energy = 0.0;           ///< J: sum I_i w_i^2 / 2
  double angularMomentum = 0.0;  ///< kg m^2/s: |(I_i w_i)|
};
SpinInvariants ComputeSpinInvariants(const Vec3& inertia, const Vec3& omega);

/// Index (0, 1, 2) of the intermediate principal moment, or -1 when two
/// moments are equal within a relative 1e-9 (no intermediate axis).
int IntermediateAxis(const Vec3& inertia);

/// Seconds between successive sign changes of the intermediate-axis
/// component of the body-frame angular velocity, i.e. between successive
/// turn-overs, for a body spun at `omega` (body frame, rad/s) mostly about
/// its intermediate axis. RK4 with 4096 steps per turn at |omega|; the
/// crossings are interpolated linearly (the component is at its steepest
/// and its curvature vanishes there). Errors: no intermediate axis, omega
/// not within 25 degrees of it, or no two flips within 10^7 steps (a
/// perturbation so small that the body stays on the unstable axis).
Result<double> IntermediateAxisFlipInterval(const Vec3& inertia, const Vec3& omega);

}  // namespace talus::harness
