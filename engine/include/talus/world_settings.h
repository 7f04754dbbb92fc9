// WorldSettings: what a user of the engine chooses, each with its unit,
// default, valid range and the reason for its default: gravity, the solver's
// iteration counts, the slop and Baumgarte factor, the restitution threshold,
// the combine rules, the broad phase, sleeping, threads and stage timing.
// How the step does its work (the method switches that keep the original
// write-up's methods selectable beside the measured improvements) lives apart
// in MethodSettings (talus/method_settings.h), WorldSettings::methods.
// WorldSettings{} is the configuration the testbed validates: its `talus`
// row runs it unchanged but for what a scenario states (gravity,
// iterations, combine rules, sleeping, the gyroscopic term, the broad
// phase; docs/testbed-backends.md, "The Talus rows").
#pragma once

#include <string>

#include "talus/broad_phase.h"
#include "talus/math.h"
#include "talus/method_settings.h"

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
  /// Least velocity iterations (Gauss-Seidel sweeps) of the sequential
  /// impulse solver, [1, 1000]. Default 10, the write-up's fixed count.
  int velocityIterations = 10;
  /// Position iterations, [1, 1000]: sweeps of the split-impulse
  /// pseudo-velocity rows (and of timed bounces' position rows). Default 10,
  /// the same budget as velocities.
  int positionIterations = 10;
  /// Baumgarte factor beta, unitless in [0, 1]: the fraction of the
  /// penetration beyond the slop removed per step. Default 0.2: larger values correct faster but add
  /// energy and jitter (Catto 2005; Box2D and Jolt use 0.2 for their
  /// position sweeps too).
  double baumgarte = 0.2;
  /// Penetration left uncorrected by Baumgarte and split impulses, metres,
  /// [0, 1]; resting contacts settle this deep. Default 0.004, measured
  /// against 5 mm (docs/dynamics.md, "The slop"): the 1000-hull pile's
  /// deepest contact 5.00-5.01 -> 4.00 mm with its kinetic energy no
  /// higher, the pyramids' drift within the same 0.1-0.6 mm, and every
  /// sweep verdict of the default variant unchanged. Much smaller turns
  /// the velocity bias into rocking (1 mm: a 10-box column falls at 10
  /// iterations; 3 mm: one hull pile repeat of three ended at 0.04 J).
  double slop = 0.004;
  /// Closing speed below which restitution is ignored, m/s, >= 0. Default
  /// 0.5: resting bodies stop micro-bouncing under gravity (g h = 0.16 m/s
  /// at 60 Hz stays well under it).
  double restitutionThreshold = 0.5;
  /// Friction combine rule. Default GeometricMean.
  FrictionCombine frictionCombine = FrictionCombine::GeometricMean;
  /// Restitution combine rule. Default Max.
  RestitutionCombine restitutionCombine = RestitutionCombine::Max;
  /// Broad phase structure. Default UniformGrid (the write-up's).
  BroadPhaseKind broadPhase = BroadPhaseKind::UniformGrid;
  /// Time each stage of the step into StepStatistics::seconds (10 clock
  /// reads a step). Default off, the fields then stay 0: the reads cost
  /// about 0.25 us a step, a fifth of a two-body step (a ball on a floor,
  /// measured with perf), for figures only a profile asks for.
  /// talus-scenes and the contact-solver benchmark turn it on.
  bool timeStages = false;
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
  /// Threads that run a step, the calling thread included, [1,
  /// kMaxThreads]. Default 1: no thread is started and the step runs on the
  /// caller alone. With more, the stages the stage table marks
  /// `workerThreads` (kStages, talus/step_stage.h) spread their work over
  /// the threads: the broad phase's proxies, the narrow phase and its
  /// gather, the rows, the coloured solver's and the soft step's sweeps and
  /// the integration; the others run on the calling thread.
  /// The result is bit-identical for every thread count: work is cut into
  /// chunks that depend on the item count only, each item writes its own
  /// slot, and results are gathered in item order (docs/threading.md).
  int threads = 1;
  /// How the step does its work (talus/method_settings.h). The defaults
  /// are the validated engine: change them to measure a method, as the
  /// testbed's variants do.
  MethodSettings methods = {};

  /// Field by field (the testbed's test that its `talus` row is these
  /// defaults compares whole settings, so a new field is covered at once).
  friend bool operator==(const WorldSettings&, const WorldSettings&) = default;
};

/// The most threads a World may use (WorldSettings::threads): far above the
/// cores of any machine this runs on; larger values are taken for typos.
inline constexpr int kMaxThreads = 256;

/// Why `settings` is invalid (names the field and the range), or an empty
/// string when it is valid.
std::string ValidateSettings(const WorldSettings& settings);

}  // namespace talus
