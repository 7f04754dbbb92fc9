// The Bullet peer behind the harness's Backend interface.
//
// Bullet 3.24: btDiscreteDynamicsWorld, btSequentialImpulseConstraintSolver,
// btDbvtBroadphase. Boxes are btBoxShape, spheres btSphereShape, hulls
// btConvexHullShape with polyhedral features. Four backends: two builds
// times two configurations.
//   - "bullet", "bullet-tuned": double precision (BT_USE_DOUBLE_PRECISION,
//     Debian's *-float64 libraries), linked in;
//   - "bullet-f32", "bullet-f32-tuned": the single-precision default build
//     most users link, from a module loaded at run time (absent from
//     sanitizer builds; BulletSinglePrecisionAvailable says).
//   - `defaults`: Bullet as a new user gets it, plus only what the scenario
//     needs to be posed (combine rules, one step of h per Step, no sleeping);
//   - `tuned`: the collision margin scaled to the scenes' bodies (1 mm
//     instead of 4 cm) and each hull shrunk by it before the margin is
//     added back: Bullet's manual warns that a hull grows by its margin and
//     that this is to be compensated; its demos shrink the hull's faces.
// Settings() lists every value with the Bullet default it replaces and its
// measured effect; docs/testbed-backends.md has the table.
#pragma once

#include "talus/harness/backend/backend.h"

namespace talus::reference {

/// Collision margin of every Bullet shape in the tuned configuration, metres
/// (the defaults keep Bullet's 0.04 m). Boxes keep their exact
/// size (btBoxShape subtracts the margin inside and adds it back, rounding
/// the corners by this radius); hulls are shrunk by it first (see
/// kBulletHullShrinkEffect), so they keep their size too. 1 mm: small
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

/// Which configuration a Bullet world is built in (see the file comment).
enum class BulletTuning { Defaults, Tuned };

/// Measured effect of the tuned margin, for Settings() and the report.
inline constexpr const char* kBulletMarginEffect =
    "hulls are inflated by the margin, so the 4 cm default holds hull_rest 0.040 m high (FAIL); 1 mm "
    "alone holds it 0.001 m high (1 FAIL removed), and the tuned hull, shrunk by the margin first (see hull "
    "shapes), rests at its geometric height. Boxes keep their size either way (the margin is subtracted "
    "inside) and spheres use their radius: no other verdict changes";

/// Measured effect of shrinking the tuned hulls by the margin, as above.
inline constexpr const char* kBulletHullShrinkEffect =
    "without it the margin grows every hull by 1 mm all round: hull_rest rested +1.000 mm above its "
    "geometric height, with it -0.007 mm (face tilt 4e-8 -> 2.5e-5 rad); no verdict changes on the suite "
    "(the 4 mm hull_rest bound passed both)";

/// Measured effect of the double-precision build, as above.
inline constexpr const char* kBulletDoubleEffect =
    "round-off only: free fall stays on the integrator-exact sequence to 4e-15 m (single: 1.6e-6 m, "
    "3 FAILs of the 1e-9 m free-fall truths) and the e = 0.9 first apex is 0.042 m low instead of "
    "0.043 m (1 FAIL); every other verdict is the same in both builds";

/// Whether this build has the single-precision module ("bullet-f32...").
bool BulletSinglePrecisionAvailable();

/// Registers "bullet", "bullet-tuned" and, where available, "bullet-f32" and
/// "bullet-f32-tuned".
void RegisterBulletBackends(harness::BackendRegistry& registry);

}  // namespace talus::reference
