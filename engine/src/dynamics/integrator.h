// The integrator: the write-up's symplectic Euler, split in the two halves
// the step puts the collision and the solver between.
//
//   v(n+1) = v(n) + h (g + F / m)           IntegrateVelocities
//   w(n+1) = w(n) + h I_world^-1 tau        (+ optional gyroscopic term)
//   x(n+1) = x(n) + h v(n+1)                IntegratePositions
//   q(n+1) = exp(h w(n+1) / 2) q(n)
//
// Velocities first, positions with the new velocities: that ordering is what
// makes the scheme symplectic (energy oscillates, it does not drift) and lets
// the solver correct velocities before they move anything. A free-falling
// body therefore follows y(n) = y0 + v0 t - g t^2 / 2 - g h t / 2 exactly.
//
// The functions touch only bodies that move (awake dynamic, kinematic); the
// forces accumulated on a body are cleared once they have been applied.
#pragma once

#include <span>

#include "dynamics/body_sim.h"
#include "talus/math.h"

namespace talus {

/// Applies gravity and accumulated forces and torques to awake dynamic
/// bodies over `h` seconds, adds the implicit gyroscopic term when
/// `gyroscopic` is on, and clears the accumulators. Returns the number of
/// bodies integrated.
int IntegrateVelocities(std::span<BodySim> bodies, const Vec3& gravity, bool gyroscopic, double h);

/// The angular velocity after `h` seconds of torque-free motion under
/// Euler's equation I dw/dt + w x (I w) = 0, by one Newton step on the
/// backward-Euler residual (Catto, "Numerical Methods", GDC 2015):
///
///   f(w2) = I (w2 - w1) + h w2 x (I w2) = 0, in body axes,
///   J = df/dw2 = I + h (skew(w2) I - skew(I w2)),
///   w2 = w1 - J(w1)^-1 f(w1) = w1 - J(w1)^-1 h w1 x (I w1).
///
/// Backward Euler damps rather than amplifies, so a tumbling body never gains
/// energy; the explicit version blows up. Returns world-space rad/s.
Vec3 GyroscopicStep(const BodySim& body, double h);

/// Moves moving bodies by their velocities (plus their split-impulse
/// pseudo-velocities when `usePseudoVelocities`), keeps orientations unit
/// and refreshes world inertia. Rotation uses the exact exponential map of
/// the constant angular velocity over the step.
void IntegratePositions(std::span<BodySim> bodies, double h, bool usePseudoVelocities);

}  // namespace talus
