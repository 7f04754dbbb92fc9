// The runner: one job per (run, backend), each in its own process or on
// the thread pool with serialised lanes for backends that are not
// thread-safe, and the per-job recording and metrics (see runner.h).
#include "talus/harness/run/runner.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

#include "support/numbers.h"
#include "support/text_util.h"
#include "talus/harness/run/job_processes.h"
#include "talus/harness/run/results_file.h"
#include "talus/harness/run/run_metrics.h"
#include "talus/harness/scenario/scenario_limits.h"
#include "talus/harness/support/nan_extremes.h"

namespace talus::harness {
namespace {

// The most per-step wall times a run keeps (8 MB): enough for a stable
// median, bounded for runs of a billion steps.
constexpr std::size_t kMaxTimedSteps = std::size_t{1} << 20;

// Serialises every call of RunnerOptions::progress (job lines and the
// long-job lines), so lines never interleave.
std::mutex& ProgressMutex() {
  static std::mutex mutex;
  return mutex;
}

bool Measures(const Run& run, Quantity quantity) {
  const auto& list = run.scenario.measure;
  return std::find(list.begin(), list.end(), quantity) != list.end();
}

PlotSeries MakeSeries(const Run& run, const Trajectory& trajectory, int plotPoints) {
  PlotSeries series;
  const Vec3 up = UpAxis(run);
  series.heights.resize(run.scenario.bodies.size());
  for (const std::size_t index :
       SpreadIndices(trajectory.samples.size(), static_cast<std::size_t>(plotPoints))) {
    const Sample& sample = trajectory.samples[index];
    series.time.push_back(sample.time);
    series.energy.push_back(sample.measures.kineticEnergy + sample.measures.potentialEnergy);
    for (std::size_t b = 0; b < sample.bodies.size(); ++b) {
      series.heights[b].push_back(sample.bodies[b].centerOfMass.dot(up));
    }
  }
  return series;
}

std::string KnownBackends(const BackendRegistry& registry) {
  std::string known;
  for (const std::string& n : registry.Names()) known.append(known.empty() ? "" : ", ").append(n);
  return known;
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string joined;
  for (const std::string& n : names) joined.append(joined.empty() ? "" : ", ").append(n);
  return joined;
}

std::string NothingToRunNotice(const Run& run, const std::vector<std::string>& asked) {
  return Concat({run.id, " (", run.scenario.file, "): not run: its backends (",
                 JoinNames(run.scenario.backends), ") and those asked for (", JoinNames(asked),
                 ") have none in common"});
}

// The first body whose state is not finite after a step, as "body \"ball\":
// non-finite position (nan, nan, nan)"; empty when every state is finite.
// Generic over backends: whatever engine produced the state, a NaN or an
// infinity ends the run here, naming the body.
std::string NonFiniteBody(const Backend& backend, const Run& run) {
  const auto describe = [](const char* what, const auto& v) {
    std::string values;
    for (Eigen::Index i = 0; i < v.size(); ++i) {
      // "nan", "inf", "-inf" as printf writes them (FormatNumber says "n/a").
      values.append(i == 0 ? "" : ", ").append(FormatPrintf("%g", v[i]));
    }
    return Concat({"non-finite ", what, " (", values, ")"});
  };
  for (int b = 0; b < backend.BodyCount(); ++b) {
    const BodyReading state = backend.GetBodyState(b);
    std::string problem;
    if (!state.origin.allFinite()) {
      problem = describe("position", state.origin);
    } else if (!state.centerOfMass.allFinite()) {
      problem = describe("centre of mass", state.centerOfMass);
    } else if (!state.orientation.coeffs().allFinite()) {
      problem = describe("orientation (x, y, z, w)", state.orientation.coeffs());
    } else if (!state.linearVelocity.allFinite()) {
      problem = describe("linear velocity", state.linearVelocity);
    } else if (!state.angularVelocity.allFinite()) {
      problem = describe("angular velocity", state.angularVelocity);
    }
    if (!problem.empty()) {
      const auto index = static_cast<std::size_t>(b);
      const std::string name =
          index < run.scenario.bodies.size() ? run.scenario.bodies[index].name : std::to_string(b);
      return Concat({"body \"", name, "\": ", problem});
    }
  }
  return {};
}

// A result with its run's identity and nothing measured yet.
RunResult ResultIdentity(const Run& run, const std::string& backendName) {
  RunResult result;
  result.scenario = run.scenario.name;
  result.file = run.scenario.file;
  result.runId = run.id;
  result.backend = backendName;
  result.sweepValues = run.sweepValues;
  result.timeStep = run.timeStep;
  result.iterations = run.iterations;
  result.steps = run.steps;
  for (const BodySpec& body : run.scenario.bodies) result.bodyNames.push_back(body.name);
  return result;
}

// The error of a job whose process died, placed like a failed step's
// ("step 63: ode-step: ...") when it died while stepping; no step number
// when it died before the first step or after the last (metrics, the
// converged reference, the answer).
std::string StoppedReason(const JobOutcome& outcome, const Run& run, const std::string& backendName) {
  std::string where;
  if (outcome.step >= 1) {
    where = Concat({"step ", std::to_string(outcome.step), ": ", backendName, ": "});
  } else if (outcome.step == kJobPastSteps) {
    where = Concat({backendName, ": after its ", std::to_string(run.steps),
                    " steps (metrics or converged reference): "});
  } else {
    where = Concat({backendName, ": before its first step: "});
  }
  std::string reason = Concat({where, outcome.failure});
  if (!outcome.lastMessage.empty()) reason.append("; last message: ").append(outcome.lastMessage);
  return reason;
}

}  // namespace

Result<std::vector<std::string>> BackendsForRun(const BackendRegistry& registry, const Run& run,
                                                const std::vector<std::string>& asked) {
  const std::vector<std::string>& listed = run.scenario.backends;
  for (std::size_t i = 0; i < listed.size(); ++i) {
    if (!registry.Has(listed[i])) {
      return Error{Concat({run.scenario.file.empty() ? run.scenario.name : run.scenario.file, ": /backends/",
                           std::to_string(i), ": unknown backend \"", listed[i],
                           "\" (known: ", KnownBackends(registry), ")"})};
    }
  }
  if (listed.empty()) return asked;
  std::vector<std::string> chosen;
  for (const std::string& name : asked) {
    if (std::find(listed.begin(), listed.end(), name) != listed.end()) chosen.push_back(name);
  }
  return chosen;
}

Result<std::vector<Run>> ExpandStepping(const std::vector<Run>& runs, const std::vector<double>& timeSteps,
                                        const std::vector<int>& iterations) {
  for (double h : timeSteps) {
    if (!(h > 0.0 && h <= 1.0)) return Error{Concat({"time step ", FormatNumber(h), " s is not in (0, 1]"})};
  }
  for (int n : iterations) {
    if (n < 0) return Error{Concat({"iterations ", std::to_string(n), " is negative (0 = engine default)"})};
  }
  if (timeSteps.empty() && iterations.empty()) return runs;
  const std::size_t perRun =
      std::max<std::size_t>(1, timeSteps.size()) * std::max<std::size_t>(1, iterations.size());
  if (perRun > kMaxRuns || runs.size() > kMaxRuns / perRun) {
    return Error{Concat({std::to_string(runs.size()), " runs x ", std::to_string(perRun),
                         " (time step, iterations) pairs is more than the limit of ",
                         std::to_string(kMaxRuns), " runs"})};
  }
  std::vector<Run> expanded;
  for (const Run& run : runs) {
    const std::vector<double> hs = timeSteps.empty() ? std::vector<double>{run.timeStep} : timeSteps;
    const std::vector<int> ns = iterations.empty() ? std::vector<int>{run.iterations} : iterations;
    const double duration = run.steps * run.timeStep;
    for (double h : hs) {
      for (int n : ns) {
        Run copy = run;
        std::string suffix;
        if (!timeSteps.empty()) {
          copy.timeStep = h;
          const double steps = std::max(1.0, std::round(duration / h));
          if (!(steps <= static_cast<double>(kMaxSteps))) {
            return Error{
                Concat({run.id, ": ", FormatNumber(duration), " s at h = ", FormatNumber(h), " s is ",
                        FormatNumber(steps), " steps, more than the limit of ", std::to_string(kMaxSteps)})};
          }
          copy.steps = static_cast<int>(steps);
          // Shortest round trip: exact, and "h=0.005" rather than
          // "h=0.0050000000000000001".
          copy.sweepValues.push_back({"h", FormatShortest(h)});
          suffix = Concat({"h=", FormatShortest(h)});
        }
        if (!iterations.empty()) {
          copy.iterations = n;
          copy.sweepValues.push_back({"iterations", std::to_string(n)});
          suffix.append(suffix.empty() ? "" : ",").append("iterations=").append(std::to_string(n));
        }
        if (!copy.id.empty() && copy.id.back() == ']') {
          copy.id.insert(copy.id.size() - 1, Concat({",", suffix}));
        } else {
          copy.id.append("[").append(suffix).append("]");
        }
        expanded.push_back(std::move(copy));
      }
    }
  }
  return expanded;
}

namespace {

// The state of every body and the world's measures at `step`, and after a
// step its contacts' count and deepest penetration; the contacts and the
// step counters themselves only with `detail` (a replay).
Sample TakeSample(Backend& backend, const Run& run, int step, double timeStep, bool detail) {
  Sample s;
  s.step = step;
  s.time = step * timeStep;
  for (int b = 0; b < backend.BodyCount(); ++b) s.bodies.push_back(backend.GetBodyState(b));
  s.measures = MeasureWorld(backend, run.scenario.world.gravity);
  if (step > 0) {
    for (const ContactReading& contact : backend.GetContacts()) {
      ++s.contactCount;
      s.maxPenetration = MaxKeepingNaN(s.maxPenetration, contact.depth);
      if (detail) s.contacts.push_back(contact);
    }
    if (detail) s.counters = backend.StepCounters();
  }
  return s;
}

// Keeps the wall time of a timed step, at most kMaxTimedSteps of them: when
// the list fills, every other entry goes and the spacing `timedEvery`
// doubles, so the memory stays bounded however long the run is.
void KeepStepTime(std::vector<double>& stepSeconds, double seconds, int& timedEvery) {
  stepSeconds.push_back(seconds);
  if (stepSeconds.size() < kMaxTimedSteps) return;
  for (std::size_t i = 0; 2 * i < stepSeconds.size(); ++i) stepSeconds[i] = stepSeconds[2 * i];
  stepSeconds.resize((stepSeconds.size() + 1) / 2);
  timedEvery *= 2;
}

}  // namespace

Trajectory Record(Backend& backend, const Run& run, int steps, double timeStep,
                  const std::function<bool(int)>& record, std::vector<double>* stepSeconds, bool detail,
                  const std::function<std::string(int, std::chrono::steady_clock::time_point)>& tick,
                  StepWallTimes* wall, bool reportSteps) {
  Trajectory trajectory;
  trajectory.timeStep = timeStep;
  trajectory.samples.push_back(TakeSample(backend, run, 0, timeStep, detail));
  int timedEvery = 1;  // the spacing of the timed steps (KeepStepTime)
  int stoppedAt = 0;   // the step `tick` stopped the recording at
  for (int step = 1; step <= steps; ++step) {
    if (reportSteps) ReportJobStep(step);
    const auto start = std::chrono::steady_clock::now();
    backend.Step();
    const auto end = std::chrono::steady_clock::now();
    if (wall != nullptr) {
      // Every step, the failing one included: a run's cost is all it spent.
      const double seconds = std::chrono::duration<double>(end - start).count();
      wall->total += seconds;
      wall->longest = std::max(wall->longest, seconds);
    }
    std::string failure = backend.StepFailure();
    if (failure.empty()) failure = NonFiniteBody(backend, run);
    if (!failure.empty()) {
      trajectory.failure = Concat({"step ", std::to_string(step), ": ", backend.Name(), ": ", failure});
      break;
    }
    if (stepSeconds != nullptr && (step - 1) % timedEvery == 0) {
      KeepStepTime(*stepSeconds, std::chrono::duration<double>(end - start).count(), timedEvery);
    }
    if (step == steps || record(step))
      trajectory.samples.push_back(TakeSample(backend, run, step, timeStep, detail));
    // Every step, on the clock reading the step's timing already took: a
    // job of slow steps (2 ms or more) checked only every 1024 steps passed
    // its budget by more than kBudgetKillGraceSeconds before the check and
    // was killed by the runner, losing its plot (issue 39).
    if (tick) {
      if (std::string stop = tick(step, end); !stop.empty()) {
        trajectory.failure = Concat({"step ", std::to_string(step), ": ", backend.Name(), ": ", stop});
        stoppedAt = step;
        break;
      }
    }
  }
  if (trajectory.samples.size() > 1) trajectory.stride = trajectory.samples[1].step;
  // A stopped job's plot ends where it stopped: with a long run's sparse
  // samples, those taken so far may be step 0 alone.
  if (stoppedAt > 0 && trajectory.samples.back().step != stoppedAt) {
    trajectory.samples.push_back(TakeSample(backend, run, stoppedAt, timeStep, detail));
  }
  return trajectory;
}

namespace {

// The tick Record calls after every step of a job: a reason to stop once
// options.budgetSeconds is spent, and a progress line every
// options.progressSeconds for a long job. Its clock starts now; `now` is
// Record's reading at the step's end, so the check costs no clock read.
std::function<std::string(int, std::chrono::steady_clock::time_point)> JobTick(const Run& run,
                                                                               const std::string& backendName,
                                                                               const RunnerOptions& options) {
  const auto begun = std::chrono::steady_clock::now();
  return [&run, &backendName, &options, begun, nextReport = options.progressSeconds](
             int step, std::chrono::steady_clock::time_point now) mutable {
    const double elapsed = std::chrono::duration<double>(now - begun).count();
    if (options.budgetSeconds > 0.0 && elapsed > options.budgetSeconds) {
      return Concat({"wall-clock budget of ", FormatNumber(options.budgetSeconds), " s spent"});
    }
    if (!options.progress || elapsed < nextReport) return std::string();
    nextReport = elapsed + options.progressSeconds;
    char line[96];
    std::snprintf(line, sizeof line, "step %d of %d (%.0f%%), %.1f s", step, run.steps,
                  100.0 * step / run.steps, elapsed);
    std::lock_guard lock(ProgressMutex());
    options.progress(Concat({run.id, " ", backendName, ": ", line}));
    return std::string();
  };
}

// The metrics of a converged-reference truth: the same backend at
// h / divisor, its samples falling on the run's sample times (every
// `stride`-th step); the error when the reference cannot be made or fails.
Result<std::vector<MetricResult>> ConvergedReferenceMetrics(const BackendRegistry& registry, const Run& run,
                                                            const std::string& backendName,
                                                            const Truth& truth,
                                                            const ConvergedReferenceTruth& converged,
                                                            const Trajectory& trajectory, int stride) {
  const int divisor = converged.timeStepDivisor;
  const long long fineSteps = static_cast<long long>(run.steps) * divisor;
  if (fineSteps > kMaxSteps) {
    return Error{Concat({"converged reference: ", std::to_string(run.steps), " steps x divisor ",
                         std::to_string(divisor), " = ", std::to_string(fineSteps),
                         " steps, more than the limit of ", std::to_string(kMaxSteps)})};
  }
  Run fine = run;
  fine.timeStep = run.timeStep / divisor;
  fine.steps = static_cast<int>(fineSteps);
  auto reference = registry.Create(backendName, fine);
  if (!reference) return Error{Concat({"converged reference: ", reference.GetError().message})};
  const Trajectory referenceTrajectory = Record(
      *reference.Value(), fine, fine.steps, fine.timeStep,
      [&](int step) { return step % divisor == 0 && IsSampled(step / divisor, run.steps, stride); }, nullptr);
  if (!referenceTrajectory.failure.empty()) {
    return Error{Concat({"converged reference: ", referenceTrajectory.failure})};
  }
  return CompareWithReference(truth, trajectory, referenceTrajectory);
}

// Every truth of the run judged on `trajectory`, gated, into
// result.metrics in the scenario's order; false (result.error set) when a
// converged reference fails.
bool JudgeTruths(const BackendRegistry& registry, const Run& run, const std::string& backendName,
                 const Trajectory& trajectory, int stride, RunResult& result) {
  for (const Truth& truth : run.scenario.truths) {
    std::vector<MetricResult> metrics;
    if (const auto* converged = std::get_if<ConvergedReferenceTruth>(&truth.kind)) {
      auto compared =
          ConvergedReferenceMetrics(registry, run, backendName, truth, *converged, trajectory, stride);
      if (!compared) {
        result.error = compared.GetError().message;
        return false;
      }
      metrics = std::move(compared).Value();
    } else {
      metrics = EvaluateTruth(run, truth, trajectory);
    }
    ApplyGate(truth, backendName, metrics);
    for (MetricResult& metric : metrics) result.metrics.push_back(std::move(metric));
  }
  return true;
}

// The quantities the scenario asks to measure ("measure"): the drifts only
// for a closed system, then penetration and contacts.
void AddMeasuredQuantities(const Run& run, const Trajectory& trajectory, RunResult& result) {
  const bool closed = IsClosedSystem(run);
  if (closed && Measures(run, Quantity::Energy)) {
    for (MetricResult& metric : EnergyDrift(trajectory)) result.metrics.push_back(std::move(metric));
  }
  if (closed && Measures(run, Quantity::Momentum)) {
    for (MetricResult& metric : MomentumDrift(run, trajectory)) result.metrics.push_back(std::move(metric));
  }
  if (Measures(run, Quantity::Penetration)) result.metrics.push_back(MaxPenetration(trajectory));
  if (Measures(run, Quantity::Contacts)) result.metrics.push_back(FinalContacts(trajectory));
}

// The run's wall-clock time and longest step (none with
// options.deterministic), kept also when the run stopped at a failed step.
void AddRunWallTime(const RunnerOptions& options, const StepWallTimes& wall, RunResult& result) {
  if (options.deterministic) return;
  result.wallSeconds = wall.total;
  result.wallSecondsLongestStep = wall.longest;
}

// The mean and median of the timed steps (none with options.deterministic).
void AddStepWallTimes(const RunnerOptions& options, const std::vector<double>& stepSeconds,
                      RunResult& result) {
  if (options.deterministic || stepSeconds.empty()) return;
  double sum = 0.0;
  for (double seconds : stepSeconds) sum += seconds;
  result.wallSecondsPerStepMean = sum / static_cast<double>(stepSeconds.size());
  result.wallSecondsPerStepMedian = Median(stepSeconds);
}

}  // namespace

RunResult RunOne(const BackendRegistry& registry, const Run& run, const std::string& backendName,
                 const RunnerOptions& options) {
  RunResult result = ResultIdentity(run, backendName);
  auto built = registry.Create(backendName, run);
  if (!built) {
    result.error = built.GetError().message;
    return result;
  }
  Backend& backend = *built.Value();
  result.settings = backend.Settings();
  const int stride = SampleStride(run.steps, options.maxSamples);
  std::vector<double> stepSeconds;
  StepWallTimes wall;
  const bool replay = IsReplaySelected(run, options.replay);
  const Trajectory trajectory = Record(
      backend, run, run.steps, run.timeStep, [&](int step) { return IsSampled(step, run.steps, stride); },
      &stepSeconds, replay, JobTick(run, backendName, options), &wall, /*reportSteps=*/true);
  ReportJobStep(kJobPastSteps);
  AddRunWallTime(options, wall, result);
  if (!trajectory.failure.empty()) {
    // The run stops at its first failed step: no metrics, but the plot up
    // to that step and the reason, which the report and the check show.
    result.error = trajectory.failure;
    result.series = MakeSeries(run, trajectory, options.plotPoints);
    return result;
  }
  if (replay) {
    auto made = MakeReplay(run, trajectory, options.replayFrames);
    if (!made) {
      result.error = Concat({"replay: ", made.GetError().message});
      return result;
    }
    result.replay = std::move(made).Value();
  }
  if (!JudgeTruths(registry, run, backendName, trajectory, stride, result)) return result;
  AddMeasuredQuantities(run, trajectory, result);
  AddStepWallTimes(options, stepSeconds, result);
  result.series = MakeSeries(run, trajectory, options.plotPoints);
  return result;
}

namespace {

// Refuses options RunAll cannot honour: unknown backends, jobs, budget or
// memory limit out of range, a memory limit without process isolation,
// sample and frame counts too small, a replay naming nothing in `runs`.
std::optional<Error> CheckRunnerOptions(const BackendRegistry& registry, const std::vector<Run>& runs,
                                        const RunnerOptions& options) {
  if (options.backends.empty()) return Error{"no backends to run"};
  for (const std::string& name : options.backends) {
    if (!registry.Has(name)) {
      return Error{Concat({"unknown backend \"", name, "\" (known: ", KnownBackends(registry), ")"})};
    }
  }
  if (options.jobs < 1 || options.jobs > kMaxJobs) {
    return Error{
        Concat({"jobs must be 1 to ", std::to_string(kMaxJobs), ", got ", std::to_string(options.jobs)})};
  }
  if (!(options.budgetSeconds >= 0.0 && options.budgetSeconds <= kMaxBudgetSeconds)) {
    return Error{Concat({"budget ", FormatNumber(options.budgetSeconds), " s is not in [0, ",
                         FormatNumber(kMaxBudgetSeconds), "] (0 = none)"})};
  }
  if (options.memoryLimitBytes != 0 &&
      (options.memoryLimitBytes < kMinMemoryLimitBytes || options.memoryLimitBytes > kMaxMemoryLimitBytes)) {
    return Error{
        Concat({"memory limit ", std::to_string(options.memoryLimitBytes), " bytes is not 0 (none) or in [",
                std::to_string(kMinMemoryLimitBytes), ", ", std::to_string(kMaxMemoryLimitBytes), "]"})};
  }
  if (options.memoryLimitBytes != 0 && options.isolation != JobIsolation::Process) {
    return Error{"a memory limit needs each job in its own process (JobIsolation::Process)"};
  }
  if (options.maxSamples < 1) return Error{"maxSamples must be >= 1"};
  if (options.plotPoints < 2) return Error{"plotPoints must be >= 2"};
  if (options.replayFrames < 2) return Error{"replayFrames must be >= 2"};
  for (const std::string& entry : options.replay) {
    if (entry == "all") continue;
    if (std::none_of(runs.begin(), runs.end(),
                     [&](const Run& run) { return run.id == entry || run.scenario.name == entry; })) {
      return Error{
          Concat({"replay: \"", entry, "\" names no run id or scenario name of this run (or give all)"})};
    }
  }
  return std::nullopt;
}

// One (run, backend) pair to run.
struct Job {
  const Run* run;
  std::string backend;
};

// The jobs in output order, every scenario's backend list checked before
// anything runs; a run no asked backend takes gives a notice.
Result<std::vector<Job>> ListJobs(const BackendRegistry& registry, const std::vector<Run>& runs,
                                  const RunnerOptions& options) {
  std::vector<Job> jobs;
  std::vector<std::string> notices;
  for (const Run& run : runs) {
    auto chosen = BackendsForRun(registry, run, options.backends);
    if (!chosen) return chosen.GetError();
    if (chosen.Value().empty()) notices.push_back(NothingToRunNotice(run, options.backends));
    for (const std::string& backend : chosen.Value()) jobs.push_back({&run, backend});
  }
  if (options.notice) {
    for (const std::string& line : notices) options.notice(line);
  }
  return jobs;
}

// "[done/total] <run id> <backend> 1.23 s", " (error)" after a job whose
// result holds an error.
std::string JobDoneLine(std::size_t done, std::size_t total, const Job& job, double seconds,
                        const RunResult& result) {
  char line[64];
  std::snprintf(line, sizeof line, " %.2f s", seconds);
  return Concat({"[", std::to_string(done), "/", std::to_string(total), "] ", job.run->id, " ", job.backend,
                 line, result.error.empty() ? "" : " (error)"});
}

// Each job in its own worker process (RunInChildProcesses): its result comes
// back serialised, or its death becomes the result's error. Each job
// writes only its own slot of `results`.
void RunJobsInProcesses(const BackendRegistry& registry, const std::vector<Job>& jobs,
                        const RunnerOptions& options, std::vector<RunResult>& results) {
  const ProcessLimits limits{
      .killAfterSeconds = options.budgetSeconds > 0.0 ? options.budgetSeconds + kBudgetKillGraceSeconds : 0.0,
      .memoryBytes = options.memoryLimitBytes};
  const auto work = [&](std::size_t index) {
    return RunResultToWire(RunOne(registry, *jobs[index].run, jobs[index].backend, options));
  };
  std::size_t done = 0;
  const auto collect = [&](std::size_t index, JobOutcome outcome) {
    const Job& job = jobs[index];
    if (outcome.finished) {
      auto answer = RunResultFromWire(outcome.answer);
      if (answer) {
        results[index] = std::move(answer).Value();
      } else {
        outcome.failure = Concat({"its answer could not be read: ", answer.GetError().message});
      }
    }
    if (!outcome.failure.empty()) {
      results[index] = ResultIdentity(*job.run, job.backend);
      results[index].error = StoppedReason(outcome, *job.run, job.backend);
    }
    if (options.progress) {
      options.progress(JobDoneLine(++done, jobs.size(), job, outcome.wallSeconds, results[index]));
    }
  };
  RunInChildProcesses(jobs.size(), options.jobs, limits, work, collect);
}

// The jobs in this process: in order on this thread with options.jobs 1,
// else on threads. Jobs of independent worlds go to a shared queue; each
// library with process-wide state gets one lane (ThreadSafety, declared at
// registration). Each job writes only its own slot of `results`.
void RunJobsOnThreads(const BackendRegistry& registry, const std::vector<Job>& jobs,
                      const RunnerOptions& options, std::vector<RunResult>& results) {
  std::size_t done = 0;
  const auto execute = [&](std::size_t index) {
    const auto start = std::chrono::steady_clock::now();
    results[index] = RunOne(registry, *jobs[index].run, jobs[index].backend, options);
    if (options.progress) {
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::lock_guard lock(ProgressMutex());
      options.progress(JobDoneLine(++done, jobs.size(), jobs[index], seconds, results[index]));
    }
  };
  if (options.jobs == 1) {
    for (std::size_t i = 0; i < jobs.size(); ++i) execute(i);
    return;
  }
  std::vector<std::size_t> freeJobs;
  std::map<std::string, std::vector<std::size_t>> lanes;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const std::string family = registry.GetThreadSafety(jobs[i].backend).sharedStateOf;
    if (family.empty()) {
      freeJobs.push_back(i);
    } else {
      lanes[family].push_back(i);
    }
  }
  std::atomic<std::size_t> next{0};
  std::vector<std::thread> threads;
  for (auto& entry : lanes) {
    // A named reference, not a structured binding: clang 14 (the fuzz
    // tree's compiler) cannot capture bindings.
    const auto& lane = entry.second;
    threads.emplace_back([&execute, &lane] {
      for (std::size_t index : lane) execute(index);
    });
  }
  // No more workers than free jobs: a thread with nothing to do is waste.
  const auto workers = std::min<std::size_t>(
      freeJobs.size(), static_cast<std::size_t>(std::max(1, options.jobs - static_cast<int>(lanes.size()))));
  for (std::size_t w = 0; w < workers; ++w) {
    threads.emplace_back([&] {
      for (std::size_t k = next++; k < freeJobs.size(); k = next++) execute(freeJobs[k]);
    });
  }
  for (std::thread& thread : threads) thread.join();
}

}  // namespace

Result<std::vector<RunResult>> RunAll(const BackendRegistry& registry, const std::vector<Run>& runs,
                                      const RunnerOptions& options) {
  if (auto refused = CheckRunnerOptions(registry, runs, options)) return *refused;
  auto jobs = ListJobs(registry, runs, options);
  if (!jobs) return jobs.GetError();
  std::vector<RunResult> results(jobs.Value().size());
  if (options.isolation == JobIsolation::Process) {
    RunJobsInProcesses(registry, jobs.Value(), options, results);
  } else {
    RunJobsOnThreads(registry, jobs.Value(), options, results);
  }
  return results;
}

}  // namespace talus::harness
