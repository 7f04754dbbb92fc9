// WorldSettings: every tunable of the dynamics in one place, each with its
// unit, default, valid range and the reason for its default. The defaults
// follow the original write-up (fixed-iteration sequential impulses with
// Baumgarte stabilisation) with the cheap, well-proven improvements (warm
// starting) switched on; every improvement can be turned off so the testbed
// can measure what it buys.
#pragma once

#include <string>

#include "talus/broad_phase.h"
#include "talus/math.h"
#include "talus/narrow_phase.h"

namespace talus {

/// How two bodies' friction coefficients make the pair's coefficient. The
/// choices cover the peers: Bullet multiplies, ODE leaves it to the user
/// (commonly min or the geometric mean), Box2D uses the geometric mean.
enum class FrictionCombine {
  GeometricMean,  ///< sqrt(f1 f2): zero when either is zero, the default
  Product,        ///< f1 f2 (Bullet)
  Min,            ///< min(f1, f2)
  Max,            ///< max(f1, f2)
  Average,        ///< (f1 + f2) / 2
};

/// How two bodies' restitution coefficients make the pair's coefficient.
enum class RestitutionCombine {
  Max,      ///< max(e1, e2): a ball bounces on any floor, the default (Box2D)
  Product,  ///< e1 e2 (Bullet)
  Min,      ///< min(e1, e2)
  Average,  ///< (e1 + e2) / 2
};

struct WorldSettings {
  /// Acceleration of gravity, m/s^2, any finite vector. Default Earth's,
  /// along -y.
  Vec3 gravity = Vec3(0.0, -9.81, 0.0);
  /// Velocity iterations of the sequential impulse solver, [1, 1000]. Default
  /// 10: a 10-box stack rests within a millimetre with warm starting.
  int velocityIterations = 10;
  /// Pseudo-velocity iterations for split impulses, [1, 1000]; used only when
  /// splitImpulses is on. Default 10, the same budget as velocities.
  int positionIterations = 10;
  /// Baumgarte factor beta, unitless in [0, 1]: the fraction of the
  /// penetration beyond `slop` removed per step. Default 0.2: larger values
  /// correct faster but add energy and jitter (Catto 2005).
  double baumgarte = 0.2;
  /// Penetration allowed without correction, metres, [0, 1]. Default 0.005:
  /// keeps contacts touching from step to step (no flicker) while staying
  /// below what the eye or a 1 mm rest-height check notices at 1 m scale.
  double slop = 0.005;
  /// Closing speed below which restitution is ignored, m/s, >= 0. Default
  /// 0.5: resting bodies stop micro-bouncing under gravity (g h = 0.16 m/s
  /// at 60 Hz stays well under it).
  double restitutionThreshold = 0.5;
  /// Carry accumulated impulses over from last step by feature id. Default
  /// on: stacks converge in a few iterations instead of hundreds.
  bool warmStarting = true;
  /// Correct penetration with pseudo-velocities that are thrown away after
  /// the position update, so the correction adds no kinetic energy. Default
  /// off (the write-up's Baumgarte bias in the velocity solve).
  bool splitImpulses = false;
  /// Add the gyroscopic term w x (I w) implicitly (one Newton step on
  /// Euler's equation, Catto GDC 2015). Default off (the write-up omits it);
  /// turn it on for tumbling, non-symmetric bodies.
  bool gyroscopic = false;
  /// Friction combine rule. Default GeometricMean.
  FrictionCombine frictionCombine = FrictionCombine::GeometricMean;
  /// Restitution combine rule. Default Max.
  RestitutionCombine restitutionCombine = RestitutionCombine::Max;
  /// Broad phase structure. Default UniformGrid (the write-up's).
  BroadPhaseKind broadPhase = BroadPhaseKind::UniformGrid;
  /// SAT mode, manifold generator, SAT cache and speculative margin (see
  /// talus/narrow_phase.h); the margin must be finite and >= 0.
  NarrowPhaseSettings narrowPhase = {};
  /// Let islands at rest fall asleep and cost nothing. Default on.
  bool sleeping = true;
  /// A body is at rest while its linear speed stays below this, m/s, >= 0.
  /// Default 0.05.
  double sleepLinearVelocity = 0.05;
  /// ... and its angular speed below this, rad/s, >= 0. Default 0.05.
  double sleepAngularVelocity = 0.05;
  /// An island sleeps after every body in it has been at rest this long,
  /// seconds, >= 0. Default 0.5: long enough that the top of a bounce
  /// (momentarily at rest) never sends a body to sleep.
  double timeToSleep = 0.5;
};

/// Why `settings` is invalid (names the field and the range), or an empty
/// string when it is valid.
std::string ValidateSettings(const WorldSettings& settings);

}  // namespace talus
