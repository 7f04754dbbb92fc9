// The ODE peer behind the harness's Backend interface, in two flavours:
// "ode-step" (dWorldStep: the global LCP solved by Dantzig's method, the kind
// of solver the original write-up contrasts with iterative ones) and
// "ode-quickstep" (dWorldQuickStep: projected Gauss-Seidel / SOR, iterative
// like Talus and Bullet).
//
// Shapes: dBox, dSphere and dConvex (planes, points and triangles of the
// qhull hull, in the centre-of-mass frame). Contacts are dContact joints
// with dContactApprox1 (mu is a coefficient, not a force limit) and
// dContactBounce from restitution. ODE's library state is initialised once
// per process (dInitODE2) and closed at exit; worlds are built and stepped
// on one thread at a time. ODE must be the double-precision build: the
// factory checks dGetConfiguration() and refuses otherwise.
#pragma once

#include "talus/harness/backend.h"

namespace talus::reference {

/// ODE's global error reduction parameter (fraction of penetration removed
/// per step). 0.2 is ODE's default and Bullet's erp2, so Baumgarte strength
/// matches across peers.
inline constexpr double kOdeErp = 0.2;

/// ODE's constraint force mixing (soft-constraint compliance, m/N per step
/// unit). 1e-10 is ODE's double-precision default: effectively hard contacts.
inline constexpr double kOdeCfm = 1e-10;

/// Depth (m) to which ODE lets contacts sink before correcting them; a
/// small layer keeps resting contacts alive from step to step instead of
/// flickering (ODE's default 0 makes quickstep jitter by ~2 mm). 1 mm:
/// below the 1 cm rest-height tolerance, like Bullet's 1 mm margin.
inline constexpr double kOdeContactSurfaceLayer = 0.001;

/// Most contact points dCollide may return per pair. Box-box needs up to 8;
/// more only multiplies rows without adding support.
inline constexpr int kOdeMaxContactsPerPair = 8;

/// Iterations of dWorldQuickStep when the run says "engine default" (ODE's
/// default).
inline constexpr int kOdeDefaultQuickStepIterations = 20;

/// Relative normal speed (m/s) below which ODE applies no bounce; the same
/// value as Bullet's restitution threshold (kRestitutionVelocityThreshold).
inline constexpr double kOdeBounceVelocity = 0.2;

/// Registers "ode-step" and "ode-quickstep".
void RegisterOdeBackends(harness::BackendRegistry& registry);

}  // namespace talus::reference
