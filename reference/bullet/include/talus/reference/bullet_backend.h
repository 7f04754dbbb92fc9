// The Bullet peer behind the harness's Backend interface.
//
// Bullet 3.24 in double precision (BT_USE_DOUBLE_PRECISION, the
// *-float64 libraries): btDiscreteDynamicsWorld, btSequentialImpulse-
// ConstraintSolver, btDbvtBroadphase. Boxes are btBoxShape, spheres
// btSphereShape, hulls btConvexHullShape with polyhedral features. Every
// place where Bullet's defaults differ from the scenario's meaning is pinned
// and listed by Settings(); docs/testbed-backends.md has the table.
#pragma once

#include "talus/harness/backend.h"

namespace talus::reference {

/// Collision margin of every Bullet shape, metres. Boxes keep their exact
/// size (btBoxShape subtracts the margin inside and adds it back, rounding
/// the corners by this radius); hulls are inflated by it. 1 mm: small
/// against the scenario sizes (>= 5 cm) yet well above round-off, which is
/// what Bullet's GJK needs to stay robust.
inline constexpr double kBulletCollisionMargin = 0.001;

/// Relative normal speed (m/s) below which Bullet applies no restitution.
/// 0.2 is Bullet's own default and above g h at 60 Hz (0.16 m/s), so a
/// resting body does not bounce on the speed gravity gives it each step.
/// ODE's bounce_vel uses the same value.
inline constexpr double kRestitutionVelocityThreshold = 0.2;

/// Solver iterations when the run says "engine default" (Bullet's default).
inline constexpr int kBulletDefaultIterations = 10;

/// Registers "bullet".
void RegisterBulletBackends(harness::BackendRegistry& registry);

}  // namespace talus::reference
