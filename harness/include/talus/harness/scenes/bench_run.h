// Running a reference benchmark scene (talus/harness/scenes/bench_scenes.h) through
// one backend and reducing it to the figures of docs/bench-scenes.md, "What
// a run reports": the cost (total wall time of the run's steps, the mean
// step, and the longest step beside it), the largest contact count of any
// step, and the scene's stability figures.
//
// The cost is the total wall time, never a median over the steps of one
// run: a median hides the landing steps, where new contacts make Talus's
// solver sweep up to maxVelocityIterations times (docs/bench-scenes.md,
// "Cost"). A median belongs only across repeated runs (bench_perturb.h).
//
// Only Backend::Step() is timed (std::chrono::steady_clock around each
// call); reading contacts and states for the figures happens between steps,
// outside the timed region. Every figure other than the times is a
// deterministic function of the backend's results. An engine that times its
// own stages (Backend::StageTimings: Talus) also gets each stage's mean and
// longest ms/step, read between steps. Every peer steps on one thread; the
// caller sets `threads` for a Talus world built with more (talus-scenes).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "talus/harness/backend/backend.h"
#include "talus/harness/scenes/bench_scenes.h"
#include "talus/result.h"

namespace talus::harness {

/// The pyramid's drift is measured from this step to the last one
/// (docs/bench-scenes.md: between step 120 and step 600; the first 2 s let
/// the layers land).
inline constexpr int kPyramidDriftStartStep = 120;

/// ODE's dWorldStep solves every island as one dense LCP (Dantzig): memory
/// grows with the square and time with up to the cube of its constraint
/// rows, and a pyramid or a settled pile is one island. Measured: the 30
/// cubes of pyramid H = 4 (about 360 contact points) already take 0.74 s
/// per step, so above this many dynamic bodies a run of "ode-step" or
/// "ode-step-tuned" is skipped with that reason printed (docs/bench-scenes.md).
inline constexpr int kOdeStepMaxBodies = 40;

/// ODE's defaults collide in a dSimpleSpace, which tests all n (n - 1) / 2
/// pairs every step. Above this many bodies runs of the ODE defaults are
/// skipped with that reason printed; the tuned ODE (dHashSpace) is not capped.
inline constexpr int kOdeMaxBodies = 5000;

/// MuJoCo 2.2.2 sizes its constraint arrays for the worst case at
/// mj_makeData (efc_AR is njmax x njmax, the stack about 5 njmax^2), and the
/// MuJoCo backend gives each dynamic body 16 contact slots, so memory grows
/// with the square of the body count: above this many dynamic bodies the
/// world would need more than its 1 GB limit (kMujocoMaxDataBytes; pyramid
/// H = 10 would need 34 GB), so MuJoCo runs are skipped with that reason.
/// 63 is where the default (pyramidal, 4 rows a contact) configuration
/// reaches the limit; pyramid H = 5 (55 cubes) and hull_pile L = 2 (40)
/// run.
inline constexpr int kMujocoMaxBodies = 63;

/// Largest solver iteration count a run may ask for (--iterations): the
/// bound of Talus's own WorldSettings::velocityIterations, [1, 1000].
inline constexpr int kBenchMaxIterations = 1000;
/// Largest number of substeps per scene step (--substeps): h / 100 is
/// 1/6000 s, and pyramid 15 at 100 substeps is already 60,000 backend steps.
inline constexpr int kBenchMaxSubsteps = 100;

/// The solver settings of one run, each engine's own knob (docs/bench-scenes.md,
/// "Iterations and substeps").
struct BenchSolver {
  /// Solver iterations (Run::iterations), 0 = the engine's own default, else
  /// in [1, kBenchMaxIterations]: Talus's velocity and position iterations,
  /// Bullet's m_numIterations, ODE quickstep's iterations per step,
  /// MuJoCo's <option iterations>. ODE's dWorldStep has none (refused).
  int iterations = 0;
  /// Backend steps per scene step, [1, kBenchMaxSubsteps]: every engine
  /// steps N times with h / N (Run::timeStep) for each step of the scene,
  /// and the N steps are timed and counted as one.
  int substeps = 1;
};

/// One stage of the engine's step over a run (Backend::StageTimings).
struct BenchStage {
  std::string name;  ///< the engine's name for it, e.g. "FindContacts"
  /// mean over the steps, milliseconds: the means of the stages add up to
  /// at most the engine's mean step, so stage mean / BenchReport::msMean is
  /// the stage's share of the run's total time
  double msMean = 0.0;
  double msMax = 0.0;  ///< its longest step, milliseconds
};

/// The initial positions of one perturbed repeat (bench_perturb.h): every
/// dynamic body moved by up to `amount` metres per axis, drawn from
/// SplitMix64 seeded with `seed` (the repeat's own seed, so that a repeat
/// is reproduced alone by `--repeats 1 --perturb-seed <seed>`).
struct BenchPerturbation {
  int repeat = 0;          ///< 0-based index in its series
  double amount = 0.0;     ///< metres, in [0, kMaxPositionPerturbation]
  std::uint64_t seed = 0;  ///< RepeatSeed(series seed, repeat)
};

/// One line of a benchmark report.
struct BenchReport {
  std::string engine;  ///< backend name, e.g. "bullet"
  std::string scene;   ///< "pyramid" or "hull_pile"
  int parameter = 0;   ///< H or L
  int bodies = 0;      ///< dynamic bodies (static floor and walls not counted)
  int threads = 1;     ///< threads the engine stepped with
  int steps = 0;       ///< steps run (scene steps of h; substeps not counted)
  BenchSolver solver;  ///< the iterations and substeps it ran with
  /// The cost: wall time of every step's Step() calls together, milliseconds.
  double totalMs = 0.0;
  double msMean = 0.0;  ///< totalMs / steps, milliseconds
  /// The longest single step, milliseconds (a landing step: new contacts).
  double msMax = 0.0;
  int maxContacts = 0;  ///< largest number of contact points reported after any step
  /// pyramid: the largest horizontal (x, z) distance any cube's centre of
  /// mass moved between step min(120, steps) and the last step, metres.
  std::optional<double> drift;
  /// hull_pile: the largest depth among the contacts after the last step,
  /// metres (0 when none penetrates).
  std::optional<double> maxPenetration;
  /// hull_pile: total kinetic energy of the dynamic bodies after the last
  /// step, joules.
  std::optional<double> kineticEnergy;
  /// hull_pile: dynamic bodies whose centre of mass ended below y = 0 or
  /// outside the walls (|x| > w or |z| > w).
  std::optional<int> escaped;
  /// Set when the run started from perturbed initial positions.
  std::optional<BenchPerturbation> perturbation;
  /// The engine's step stages in its order; empty for an engine that does
  /// not time them (every peer).
  std::vector<BenchStage> stages;
  /// Not empty when the run was not made: why (then only the identity
  /// fields above are filled).
  std::string skipped;
};

/// Why `engine` is not run on a scene of `dynamicBodies` bodies, or nothing
/// when it is (see kOdeStepMaxBodies, kOdeMaxBodies, kMujocoMaxBodies).
std::optional<std::string> BenchSkipReason(std::string_view engine, int dynamicBodies);

/// Why `solver` cannot be run on `engine`, or nothing when it can: an
/// iteration count outside [0, kBenchMaxIterations] or a substep count
/// outside [1, kBenchMaxSubsteps] (named with its value and range), or
/// iterations asked of ODE's dWorldStep ("ode-step", "ode-step-tuned"),
/// which solves each island directly and has no iteration count.
std::optional<std::string> BenchSolverProblem(std::string_view engine, const BenchSolver& solver);

/// "engine default" or "8 iterations", and ", 2 substeps" when more than one.
std::string BenchSolverLabel(const BenchSolver& solver);

/// Called after every step with the step number (1-based) and the total;
/// may be empty.
using BenchProgress = std::function<void(int step, int steps)>;

/// Builds `scene` at `parameter` with the named backend, runs `steps` steps
/// (>= 1) with `solver` and reports. A parameter out of range, an unknown
/// engine, a BenchSolverProblem, a world the backend refuses, or stage
/// timings that change their stages from one step to the next is an Error. When BenchSkipReason says so, the
/// report comes back with `skipped` set and nothing run. With a `perturbation`, the scene's dynamic bodies
/// start from PerturbDynamicPositions(amount, seed) and the report carries it; a bad amount is an Error.
Result<BenchReport> RunBenchScene(const BackendRegistry& registry, std::string_view engine,
                                  const BenchScene& scene, int parameter, int steps,
                                  const BenchProgress& progress = {},
                                  const std::optional<BenchPerturbation>& perturbation = std::nullopt,
                                  const BenchSolver& solver = {});

}  // namespace talus::harness
