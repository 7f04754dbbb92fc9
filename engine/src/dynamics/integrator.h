// The integrator: the write-up's symplectic Euler, split in the two halves
// the step puts the collision and the solver between, with a choice of
// rotation and translation schemes (talus/world_settings.h).
//
//   v(n+1) = v(n) + h (g + F / m)           IntegrateVelocities
//   w(n+1) = w(n) + h I_world^-1 tau
//   x(n+1) = x(n) + h v(n+1)                IntegratePositions
//   q(n+1) = exp(h w(n+1) / 2) q(n)         (ConstantRate)
//
// Velocities first, positions with the new velocities: that ordering is what
// makes the scheme symplectic (energy oscillates, it does not drift) and lets
// the solver correct velocities before they move anything. A free-falling
// body therefore follows y(n) = y0 + v0 t - g t^2 / 2 - g h t / 2 exactly.
//
// Two alternatives replace parts of the drift:
//
// * MomentumSplitting (rotation): the solved w is turned into the world
//   angular momentum L = I_world(q(n)) w(n+1), which a free body keeps. Its
//   body-frame image pi = (R P)^T L (P: principal axes) then moves under
//   the free rigid body's Hamiltonian H = sum pi_i^2 / (2 I_i), split as
//   H1 + H2 + H3 (Dullweber, Leimkuhler and McLachlan 1997). Each H_i's flow
//   is exact: the body turns about its principal axis i by t pi_i / I_i
//   while pi turns back by the same angle, so R P pi = L is unchanged by
//   every sub-flow. Strang's symmetric composition
//   H1(h/2) H2(h/2) H3(h) H2(h/2) H1(h/2) is symplectic and second order:
//   L is conserved to round-off, the energy error is O(h^2) and bounded
//   (backward error analysis: the scheme is the exact flow of a nearby
//   Hamiltonian). Afterwards w(n+1) = I_world(q(n+1))^-1 L, so the body
//   leaves the step with the angular velocity of its new attitude.
// * MomentumSplittingFourthOrder (rotation): the same drift with the Strang
//   step composed by Yoshida's triple jump, S(a h) S(b h) S(a h) with
//   a = 1 / (2 - 2^(1/3)), b = 1 - 2a: every sub-flow is still an exact
//   rotation that keeps L, and the h^3 term of the local error cancels, so
//   the energy error is O(h^4) (13 sub-rotations a step against 5).
// * ExactConstantAcceleration (translation; the default): a body whose
//   velocity the contact solver left unchanged moves by
//   h (v(n) + v(n+1)) / 2, which for a constant acceleration a is
//   h v(n) + a h^2 / 2: the parabola, exactly.
//   A body an impulse acted on moves by h v(n+1), the solved velocity, so
//   speculative gaps and resting contacts mean what the solver assumed.
//
// The functions touch only bodies that move (awake dynamic, kinematic); the
// forces accumulated on a body are cleared once they have been applied.
#pragma once

#include <span>

#include "dynamics/body_sim.h"
#include "talus/math.h"
#include "talus/world_settings.h"

namespace talus {

/// Applies gravity and accumulated forces and torques to awake dynamic
/// bodies over `h` seconds, records the start and free linear velocities,
/// and clears the accumulators (the gyroscopic term, when selected, is in
/// the rotation drift of IntegratePositions). Returns the number of bodies
/// integrated.
int IntegrateVelocities(std::span<BodySim> bodies, const Vec3& gravity, double h);

/// The principal axes of a symmetric positive definite inertia (kg m^2,
/// body axes): `frame` maps principal-axes vectors to body axes (a proper
/// rotation) and `moments` are the principal moments. A diagonal inertia
/// gives the identity and its diagonal exactly, so boxes carry no round-off.
struct PrincipalAxes {
  Quat frame = Quat::Identity();
  Vec3 moments = Vec3::Zero();
};
PrincipalAxes ComputePrincipalAxes(const Mat3& inertia);

/// The order of the free rigid body drift: Strang's symmetric splitting
/// (second) or Yoshida's triple jump of it (fourth).
enum class SplittingOrder { Second, Fourth };

/// The free rigid body drift of MomentumSplitting (or, with
/// SplittingOrder::Fourth, MomentumSplittingFourthOrder) over `h` seconds
/// for a body at `orientation` with principal axes `principal` and world
/// angular momentum `momentum` (kg m^2/s): the new orientation (unit) and
/// the angular velocity (world, rad/s) of that orientation with the same L.
/// Equal principal moments take the exact flow instead (one turn at the
/// constant rate L / I), and L = 0 returns `orientation` unchanged.
struct FreeRotation {
  Quat orientation = Quat::Identity();
  Vec3 angularVelocity = Vec3::Zero();
};
FreeRotation SplitFreeRotation(const Quat& orientation, const PrincipalAxes& principal, const Vec3& momentum,
                               double h, SplittingOrder order = SplittingOrder::Second);

/// Moves moving bodies by their velocities (plus their split-impulse
/// pseudo-velocities when `usePseudoVelocities`) with the chosen schemes,
/// keeps orientations unit and refreshes world inertia. Kinematic bodies and
/// the pseudo-velocities always use the exact exponential of a constant rate.
void IntegratePositions(std::span<BodySim> bodies, double h, bool usePseudoVelocities,
                        RotationIntegrator rotation, TranslationIntegrator translation);

}  // namespace talus
