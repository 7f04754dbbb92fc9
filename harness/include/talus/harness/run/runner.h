// The runner: runs scenarios x backends (x sweep values, already expanded
// into Runs by the loader) and records, per run and backend, a trajectory,
// the metrics the scenario asks for and the wall time per step. A run goes
// to the backends asked for that its scenario also lists (all asked for
// when it lists none).
//
// Work is split into independent jobs, one per (run, backend); results
// come back in job order (runs in file order, backends in the order asked
// for) whatever the timing, so the output is deterministic. By default
// (JobIsolation::Process) each job runs in its own child process
// (job_processes.h), so an engine that aborts, segfaults, hangs past the
// budget or runs out of its memory limit stops only its own job, which
// then records the cause as its error. JobIsolation::InProcess runs the
// jobs on a pool of threads in this process instead (what the
// ThreadSanitizer tree checks): each backend declares its thread safety
// where it registers (ThreadSafety, backend.h), and the jobs of backends
// whose worlds share a library's process-wide state (ODE, Bullet, MuJoCo)
// run in order on one dedicated thread per library, concurrently with the
// other libraries and with the jobs of independent worlds (Talus's).
#pragma once

#include <chrono>
#include <cstddef>

#include <functional>
#include <string>
#include <vector>

#include "talus/harness/backend/backend.h"
#include "talus/harness/backend/trajectory.h"
#include "talus/harness/run/replay.h"
#include "talus/harness/scenario/scenario.h"
#include "talus/harness/truth/truth_check.h"
#include "talus/result.h"

namespace talus::harness {

/// A thinned time series for plots: at most RunnerOptions::plotPoints points.
struct PlotSeries {
  std::vector<double> time;                  ///< seconds
  std::vector<std::vector<double>> heights;  ///< per scenario body: centre of mass along the up axis, m
  std::vector<double> energy;                ///< J: kinetic + potential of the dynamic bodies
};

/// A sweep point's perturbed copies (sweep/perturbed_copies.h), folded
/// into the unperturbed run's result; copies == 0 for every other result.
struct PerturbedRuns {
  int copies = 0;                  ///< perturbed copies run besides the unperturbed run
  double amount = 0.0;             ///< m: each coordinate moved by at most this
  double errorSpread = 0.0;        ///< max - min of the error scalar over the run and its copies
  std::vector<double> runSeconds;  ///< per run (unperturbed first): its total wall seconds
  /// Per run (unperturbed first): its error scalar (sweep.h RunErrorScalar),
  /// +infinity for a run that failed or could not be measured. Empty in
  /// files written before it was recorded.
  std::vector<double> errors;
};

/// Everything one (run, backend) job produced.
struct RunResult {
  std::string scenario;                 ///< scenario name
  std::string file;                     ///< scenario file as given
  std::string runId;                    ///< e.g. "box_slide[mu=0.3,v0=1]"
  std::string backend;                  ///< registry name
  std::vector<SweepValue> sweepValues;  ///< the run's sweep values
  double timeStep = 0.0;                ///< seconds
  int iterations = 0;                   ///< as asked (0 = engine default; the settings say what it was)
  int steps = 0;                        ///< steps taken
  std::vector<std::string> bodyNames;   ///< scenario order
  std::vector<Setting> settings;        ///< the backend's, in its order
  std::string error;  ///< why it failed: refused, or "step N: engine: reason"; no metrics then
  std::vector<MetricResult> metrics;      ///< truths first (file order), then drift, penetration, contacts
  double wallSecondsPerStepMedian = 0.0;  ///< seconds; 0 in deterministic mode
  double wallSecondsPerStepMean = 0.0;    ///< seconds; 0 in deterministic mode
  /// Seconds: the sum of every step's wall time, the run's cost (also of a
  /// run that failed: the steps up to the failure); 0 in deterministic
  /// mode. With perturbed copies, the median over the run and its copies.
  double wallSeconds = 0.0;
  /// Seconds: the longest single step (0 in deterministic mode, NaN when the
  /// file predates it); with perturbed copies, the longest of all the runs'.
  double wallSecondsLongestStep = 0.0;
  PerturbedRuns perturbed;
  PlotSeries series;  ///< for the HTML report
  Replay replay;      ///< for the 3D replay; empty unless selected (RunnerOptions::replay)
};

/// Where RunAll's jobs run (see the file comment).
enum class JobIsolation {
  Process,    ///< one child process per job: a crash, hang or runaway allocation stops that job only
  InProcess,  ///< threads of this process: no protection, no fork (ThreadSanitizer, debuggers)
};

/// Bounds of RunnerOptions::budgetSeconds and memoryLimitBytes (0 = none
/// for both). A limit below 16 MiB leaves no room for an engine's own
/// start-up allocations; the upper bounds only keep the numbers sane (11.6
/// days, 1 TiB).
inline constexpr double kMaxBudgetSeconds = 1e6;
inline constexpr std::size_t kMinMemoryLimitBytes = std::size_t{16} << 20;
inline constexpr std::size_t kMaxMemoryLimitBytes = std::size_t{1} << 40;
/// With JobIsolation::Process, the runner kills a job's process this long
/// after its budget: the job's own check (after every step) stops it first
/// and keeps its plot; the kill ends a job stuck inside one step.
inline constexpr double kBudgetKillGraceSeconds = 2.0;

struct RunnerOptions {
  /// Backends to run, in output order; each must be registered.
  std::vector<std::string> backends;
  /// Threads in all, >= 1; 1 runs everything on the calling thread.
  int jobs = 1;
  /// Zero every wall time, so two runs give byte-identical results.
  bool deterministic = false;
  /// Most samples a trajectory keeps (the stride grows for long runs), >= 1.
  int maxSamples = 2000;
  /// Most points of each plot series, >= 2.
  int plotPoints = 200;
  /// Runs whose replay (poses, contacts, step counters) is recorded: run
  /// ids, scenario names, or "all"; empty (default) records none.
  std::vector<std::string> replay;
  /// Most frames of a replay, >= 2: the display rate of the 3D replay,
  /// which interpolates poses between frames as it plays, so 60 frames
  /// (6 a second over the 10 s box_pyramid_4, 60 over the 1 s free fall)
  /// move smoothly; more only add bytes (docs/testbed-report.md "Sizes").
  int replayFrames = 60;
  /// Called (serialised) after each job with a line such as
  /// "[3/24] box_slide[mu=0.3,v0=1] bullet 0.12 s"; may be empty.
  std::function<void(const std::string&)> progress;
  /// While a job runs longer than this, `progress` also gets a line such
  /// as "box_slide bullet: step 120000 of 1000000 (12%), 10.0 s" every
  /// this many seconds (serialised with the other lines).
  double progressSeconds = 10.0;
  /// Wall-clock budget of one job's recorded run, seconds, in [0,
  /// kMaxBudgetSeconds]; 0 = none. A job past it stops like a failed step:
  /// "step 3072: talus: wall-clock budget of 60 s spent" (checked after
  /// every step, its plot kept up to there). With JobIsolation::Process, a job still running
  /// kBudgetKillGraceSeconds later (stuck inside one step) is killed:
  /// "step 12: ode-quickstep: wall-clock budget spent: the runner killed
  /// the job's process after 62 s".
  double budgetSeconds = 0.0;
  /// Where the jobs run.
  JobIsolation isolation = JobIsolation::Process;
  /// With JobIsolation::Process: the address space each job's process may
  /// add to what it starts with (RLIMIT_AS), bytes; 0 = none, else in
  /// [kMinMemoryLimitBytes, kMaxMemoryLimitBytes]. An allocation past it
  /// fails; a job ended by it records "ran out of memory (std::bad_alloc)
  /// within the job's limit of 256 MiB" or the engine's own reaction (ODE
  /// reports a step it could not take). Must be 0 with InProcess.
  std::size_t memoryLimitBytes = 0;
  /// Called on the calling thread, before any job runs, once per run that
  /// runs on no backend because its scenario's `backends` and `backends`
  /// above have no name in common (such a run has no RunResult), e.g.
  /// "box_rest (scenarios/stacking/box_rest.json): not run: its backends
  /// (bullet) and those asked for (talus) have none in common"; may be empty.
  std::function<void(const std::string&)> notice;
};

/// The runs again for every (time step, iterations) pair: each run's
/// duration is kept (steps = round(duration / h), at least 1), its
/// iterations replaced (0 = engine default), and "h" and "iterations" are
/// added to its sweep values and id ("box_slide[mu=0.3,h=0.01,iterations=5]").
/// An empty list keeps the runs' own values for that axis. Time steps must
/// be in (0, 1] and iterations >= 0, else an Error naming the value.
Result<std::vector<Run>> ExpandStepping(const std::vector<Run>& runs, const std::vector<double>& timeSteps,
                                        const std::vector<int>& iterations);

/// The backends `run` runs on: the names of `asked` (in that order) that
/// its scenario's `backends` lists, or all of `asked` when it lists none;
/// possibly none. A listed name the registry does not know is an Error
/// naming the file and field, e.g. "box.json: /backends/1: unknown backend
/// \"havok\" (known: ...)".
Result<std::vector<std::string>> BackendsForRun(const BackendRegistry& registry, const Run& run,
                                                const std::vector<std::string>& asked);

/// Runs every run with each backend BackendsForRun gives it from
/// `options.backends`. An unknown backend name (asked for or in a scenario)
/// or bad options is an Error before anything runs; a run left with no
/// backend is passed to options.notice and has no result; a backend
/// refusing one run is recorded in that RunResult's `error`, and so (with
/// JobIsolation::Process) is a job whose process died: "step 63: ode-step:
/// stopped by signal 6 (SIGABRT: Aborted); last message: ...", with the
/// step it had reached, the signal or limit, and the last lines the engine
/// wrote to stderr. Such a result keeps its run's identity (scenario, run,
/// backend, steps, bodies) but no settings, metrics or plot. With Process
/// isolation the calling thread must be the process's only thread.
Result<std::vector<RunResult>> RunAll(const BackendRegistry& registry, const std::vector<Run>& runs,
                                      const RunnerOptions& options);

/// Runs one run with one backend (what each job does): the trajectory, its
/// metrics and timings (samples thinned to options.maxSamples).
RunResult RunOne(const BackendRegistry& registry, const Run& run, const std::string& backend,
                 const RunnerOptions& options);

/// Steps a built backend through `steps` steps, recording the samples for
/// which `record(step)` holds (step 0 and the last always) and, when
/// `stepSeconds` is not null, the wall time of every step. With `detail`,
/// each sample also keeps its contacts and the backend's step counters.
/// `tick`, when set, is called after every step with the step number and
/// the clock reading taken as that step ended (no clock read of its own);
/// a non-empty answer stops the recording with that reason, and the state
/// at that step ends the trajectory (a sample of it is added if that step
/// was not sampled). The first failed
/// step or non-finite body state stops it too (Trajectory::failure).
/// `wall`, when not null, gets the total and the longest of every step's
/// wall time (every step, not only those kept in `stepSeconds`). With
/// `reportSteps`, each step's number goes to the runner's parent process
/// before the step is taken (ReportJobStep, job_processes.h), so a job
/// that dies is placed at its step; RunOne asks it for the run it records,
/// not for a converged reference.
struct StepWallTimes {
  double total = 0.0;    ///< seconds
  double longest = 0.0;  ///< seconds
};
Trajectory Record(Backend& backend, const Run& run, int steps, double timeStep,
                  const std::function<bool(int)>& record, std::vector<double>* stepSeconds,
                  bool detail = false,
                  const std::function<std::string(int, std::chrono::steady_clock::time_point)>& tick = {},
                  StepWallTimes* wall = nullptr, bool reportSteps = false);

}  // namespace talus::harness
