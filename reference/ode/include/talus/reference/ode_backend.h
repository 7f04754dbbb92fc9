// The ODE peer behind the harness's Backend interface: two steppers,
// "ode-step" (dWorldStep: the global LCP solved by Dantzig's method, the kind
// of solver the original write-up contrasts with iterative ones) and
// "ode-quickstep" (dWorldQuickStep: projected Gauss-Seidel / SOR, iterative
// like Talus and Bullet), each in two configurations:
//   - `defaults` ("ode-step", "ode-quickstep"): what a new ODE user gets, plus
//     only what the scenario needs to be posed (mu as a coefficient, the
//     combine rules, restitution, no auto-disable): dSimpleSpace, ODE's
//     friction pyramid on its own tangent axes, every world parameter at
//     ODE's default;
//   - `tuned` ("ode-step-tuned", "ode-quickstep-tuned"): ODE's documented
//     practice for Coulomb friction and many bodies: the first friction
//     direction along the slip velocity (dContactFDir1), so the pyramid's
//     edge is the sliding direction, and dHashSpace.
// Settings() lists every value with the engine default it replaces and the
// measured effect (docs/testbed-backends.md has the table).
//
// Shapes: dBox, dSphere and dConvex (planes, points and face polygons of
// the qhull hull, in the centre-of-mass frame). Contacts are dContact joints
// with dContactApprox1 (mu is a coefficient, not a force limit) and
// dContactBounce from restitution. ODE's library state is initialised once
// per process (dInitODE2) and closed at exit; worlds are built and stepped
// on one thread at a time. ODE must be the double-precision build: the
// factory checks dGetConfiguration() and refuses otherwise.
#pragma once

#include "talus/harness/backend/backend.h"

namespace talus::reference {

/// ODE's global error reduction parameter (fraction of penetration removed
/// per step). 0.2 is ODE's default and Bullet's erp2, so Baumgarte strength
/// matches across peers.
inline constexpr double kOdeErp = 0.2;

/// ODE's constraint force mixing (soft-constraint compliance, m/N per step
/// unit). 1e-10 is ODE's double-precision default: effectively hard contacts.
inline constexpr double kOdeCfm = 1e-10;

/// Depth (m) to which the tuned quickstep lets contacts sink before
/// correcting them. ODE's manual advises a small layer (its example: 0.001)
/// against jitter from contacts made and broken every step; quickstep at
/// ODE's default 0 jitters by more than 1 mm on a resting box. dWorldStep
/// keeps 0 in both configurations: with 1 mm its Dantzig solver reports
/// "LCP internal error" and the 5-box column falls (measured, see
/// docs/testbed-backends.md).
inline constexpr double kOdeTunedQuickStepSurfaceLayer = 0.001;

/// Slip speed (m/s) below which a tuned contact keeps ODE's own tangent
/// axes: a slower relative tangential velocity has no meaningful direction
/// (1e-9 m/s is ~1e-7 of g h at 1 kHz, far below any sliding speed the
/// scenarios ask about and far above round-off on velocities of ~1 m/s).
/// Not tuned to the verdicts: quickstep's move at the millimetre level with
/// it (measured, docs/testbed-backends.md), e.g. the 30-degree box_incline
/// slide ends 0.177 m short at 1e-9 and 1e-4 m/s and 0.003 m long from
/// 1e-3 m/s up, while box_rest's jitter grows from 0.02 mm to 1.17 mm.
inline constexpr double kOdeSlipSpeedFloor = 1e-9;

/// dHashSpace cell levels of the tuned configuration: cells from 2^-3 m to
/// 2^10 m, ODE's own defaults, set explicitly so the record is exact.
inline constexpr int kOdeHashMinLevel = -3;
inline constexpr int kOdeHashMaxLevel = 10;

/// Measured effect of the tuned friction direction, for Settings() and the
/// report (docs/testbed-backends.md "Measured effects" has the commands).
inline constexpr const char* kOdeFdir1Effect =
    "the friction pyramid's edge follows the slide, so friction is mu N against the slip in every "
    "direction: on the 8 diagonal box_slide_directions runs the stop-distance error goes from -0.192 m "
    "to 3e-11 m (dWorldStep) and at most 0.004 m (quickstep), the sideways drift from 0.145 m to 1e-15 m "
    "and 0.003 m: 24 FAILs removed per stepper. With quickstep and its 1 mm surface layer the slides on "
    "the slope end short: 35 degrees 0.070 m (defaults 0.003 m; tolerance 0.042 m), 1 FAIL added; 30 "
    "degrees 0.177 m (defaults 0.025 m long, also a FAIL). ODE's own quickstep behaviour under its "
    "documented practice: without the layer 0.031 m at 35 degrees, without FDir1 0.039 m, and dropping "
    "either gives back more FAILs than it removes";

/// Measured effect of the hash space, as above.
inline constexpr const char* kOdeHashSpaceEffect =
    "it tests the pairs whose cells meet instead of all n(n-1)/2 (speed), and the near callback gets "
    "the pairs in the hash space's own order, as an ODE user's does (deterministic run to run). "
    "dWorldStep's stability depends on that order: on box_pyramid_4 the hash space's order stands "
    "(0 FAILs), the same pairs sorted by body index lose 3 height truths; the 10-box column falls "
    "in every order (8 height FAILs with dSimpleSpace, 9 here: where collapsed boxes land is chaotic)";

/// Measured effect of the tuned quickstep's surface layer, as above.
inline constexpr const char* kOdeSurfaceLayerEffect =
    "ODE's advice against contacts made and broken each step: box_rest's jitter 0.02 mm instead of "
    "1.61 mm and box_pyramid_4's drift 8.3 mm instead of 11.0 mm (2 FAILs removed), the 10-box "
    "column's drift 11.4 mm instead of 24.6 mm (still a FAIL), the 35-degree incline slides 0.070 m "
    "short instead of 0.031 m (1 FAIL added, see the friction directions). Not used with dWorldStep: "
    "there it makes the Dantzig solver report LCP internal errors and the 5-box column fall";

/// Which configuration an ODE world is built in (see the file comment).
enum class OdeTuning { Defaults, Tuned };

/// Most contact points dCollide may return per pair. Box-box needs up to 8;
/// more only multiplies rows without adding support.
inline constexpr int kOdeMaxContactsPerPair = 8;

/// Iterations of dWorldQuickStep when the run says "engine default" (ODE's
/// default).
inline constexpr int kOdeDefaultQuickStepIterations = 20;

/// Relative normal speed (m/s) below which ODE applies no bounce; the same
/// value as Bullet's restitution threshold (kRestitutionVelocityThreshold).
inline constexpr double kOdeBounceVelocity = 0.2;

/// Registers "ode-step", "ode-quickstep" (defaults) and "ode-step-tuned",
/// "ode-quickstep-tuned".
void RegisterOdeBackends(harness::BackendRegistry& registry);

}  // namespace talus::reference
