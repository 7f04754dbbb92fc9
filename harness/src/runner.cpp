// The runner: scenario discovery, one job per (run, backend), the thread
// pool with serialised lanes for backends that are not thread-safe, and
// the per-job recording and metrics (see runner.h).
#include "talus/harness/runner.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <thread>
#include <utility>

#include "talus/harness/run_metrics.h"
#include "talus/harness/scenario_loader.h"
#include "text_util.h"

namespace talus::harness {
namespace {

namespace fs = std::filesystem;

bool Measures(const Run& run, Quantity quantity) {
  const auto& list = run.scenario.measure;
  return std::find(list.begin(), list.end(), quantity) != list.end();
}

// The family of a backend ("ode-step" -> "ode"); "" for the thread-safe
// Talus backends, whose worlds share no state.
std::string SerialFamily(const std::string& backend) {
  const std::string family = backend.substr(0, backend.find('-'));
  return family == "talus" ? std::string() : family;
}

double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  double median = values[mid];
  if (values.size() % 2 == 0) {
    median =
        0.5 * (median + *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid)));
  }
  return median;
}

PlotSeries MakeSeries(const Run& run, const Trajectory& trajectory, int plotPoints) {
  PlotSeries series;
  const std::size_t count = trajectory.samples.size();
  const auto points = std::min(count, static_cast<std::size_t>(plotPoints));
  const Vec3 up = UpAxis(run);
  series.heights.resize(run.scenario.bodies.size());
  std::size_t last = count;  // no index yet
  for (std::size_t i = 0; i < points; ++i) {
    const std::size_t index = points == 1 ? 0 : i * (count - 1) / (points - 1);
    if (index == last) continue;
    last = index;
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

Result<std::vector<Run>> LoadScenarios(const std::vector<fs::path>& paths) {
  std::vector<fs::path> files;
  for (const fs::path& path : paths) {
    std::error_code error;
    if (fs::is_directory(path, error)) {
      std::vector<fs::path> found;
      for (auto it = fs::recursive_directory_iterator(path, error); !error && it != fs::end(it);
           it.increment(error)) {
        if (it->is_regular_file() && it->path().extension() == ".json" &&
            it->path().filename() != "schema.json") {
          found.push_back(it->path());
        }
      }
      if (error) return Error{Concat({path.string(), ": ", error.message()})};
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else if (fs::is_regular_file(path, error)) {
      files.push_back(path);
    } else {
      return Error{Concat({path.string(), ": no such scenario file or folder"})};
    }
  }
  if (files.empty()) return Error{"no scenario files found"};
  std::vector<Run> runs;
  for (const fs::path& file : files) {
    auto loaded = LoadScenarioFile(file);
    if (!loaded) return loaded.GetError();
    for (Run& run : loaded.Value()) runs.push_back(std::move(run));
  }
  return runs;
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
          copy.steps = std::max(1, static_cast<int>(std::lround(duration / h)));
          copy.sweepValues.push_back({"h", FormatNumber(h, 17)});
          suffix = Concat({"h=", FormatNumber(h, 17)});
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

Trajectory Record(Backend& backend, const Run& run, int steps, double timeStep,
                  const std::function<bool(int)>& record, std::vector<double>* stepSeconds, bool detail) {
  Trajectory trajectory;
  trajectory.timeStep = timeStep;
  const auto sample = [&](int step) {
    Sample s;
    s.step = step;
    s.time = step * timeStep;
    for (int b = 0; b < backend.BodyCount(); ++b) s.bodies.push_back(backend.GetBodyState(b));
    s.measures = MeasureWorld(backend, run.scenario.world.gravity);
    if (step > 0) {
      for (const ContactPoint& contact : backend.GetContacts()) {
        ++s.contactCount;
        s.maxPenetration = std::max(s.maxPenetration, contact.depth);
        if (detail) s.contacts.push_back(contact);
      }
      if (detail) s.counters = backend.StepCounters();
    }
    trajectory.samples.push_back(std::move(s));
  };
  sample(0);
  if (stepSeconds != nullptr) stepSeconds->reserve(static_cast<std::size_t>(steps));
  for (int step = 1; step <= steps; ++step) {
    const auto start = std::chrono::steady_clock::now();
    backend.Step();
    if (stepSeconds != nullptr) {
      stepSeconds->push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    if (step == steps || record(step)) sample(step);
  }
  if (trajectory.samples.size() > 1) trajectory.stride = trajectory.samples[1].step;
  return trajectory;
}

RunResult RunOne(const BackendRegistry& registry, const Run& run, const std::string& backendName,
                 const RunnerOptions& options) {
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

  auto built = registry.Create(backendName, run);
  if (!built) {
    result.error = built.GetError().message;
    return result;
  }
  Backend& backend = *built.Value();
  result.settings = backend.Settings();
  const int stride = SampleStride(run.steps, options.maxSamples);
  std::vector<double> stepSeconds;
  const bool replay = IsReplaySelected(run, options.replay);
  const Trajectory trajectory = Record(
      backend, run, run.steps, run.timeStep, [&](int step) { return IsSampled(step, run.steps, stride); },
      &stepSeconds, replay);
  if (replay) {
    auto made = MakeReplay(run, trajectory, options.replayFrames);
    if (!made) {
      result.error = Concat({"replay: ", made.GetError().message});
      return result;
    }
    result.replay = std::move(made).Value();
  }

  for (const Truth& truth : run.scenario.truths) {
    if (const auto* converged = std::get_if<ConvergedReferenceTruth>(&truth.kind)) {
      // The same backend at h / divisor; its samples fall on our sample times.
      const int divisor = converged->timeStepDivisor;
      Run fine = run;
      fine.timeStep = run.timeStep / divisor;
      fine.steps = run.steps * divisor;
      auto reference = registry.Create(backendName, fine);
      if (!reference) {
        result.error = Concat({"converged reference: ", reference.GetError().message});
        return result;
      }
      const Trajectory referenceTrajectory = Record(
          *reference.Value(), fine, fine.steps, fine.timeStep,
          [&](int step) { return step % divisor == 0 && IsSampled(step / divisor, run.steps, stride); },
          nullptr);
      std::vector<MetricResult> metrics = CompareWithReference(truth, trajectory, referenceTrajectory);
      ApplyGate(truth, backendName, metrics);
      for (MetricResult& metric : metrics) result.metrics.push_back(std::move(metric));
    } else {
      std::vector<MetricResult> metrics = EvaluateTruth(run, truth, trajectory);
      ApplyGate(truth, backendName, metrics);
      for (MetricResult& metric : metrics) result.metrics.push_back(std::move(metric));
    }
  }
  const bool closed = IsClosedSystem(run);
  if (closed && Measures(run, Quantity::Energy)) {
    for (MetricResult& metric : EnergyDrift(trajectory)) result.metrics.push_back(std::move(metric));
  }
  if (closed && Measures(run, Quantity::Momentum)) {
    for (MetricResult& metric : MomentumDrift(run, trajectory)) result.metrics.push_back(std::move(metric));
  }
  if (Measures(run, Quantity::Penetration)) result.metrics.push_back(MaxPenetration(trajectory));
  if (Measures(run, Quantity::Contacts)) result.metrics.push_back(FinalContacts(trajectory));

  if (!options.deterministic && !stepSeconds.empty()) {
    double sum = 0.0;
    for (double seconds : stepSeconds) sum += seconds;
    result.wallSecondsPerStepMean = sum / static_cast<double>(stepSeconds.size());
    result.wallSecondsPerStepMedian = Median(stepSeconds);
  }
  result.series = MakeSeries(run, trajectory, options.plotPoints);
  return result;
}

Result<std::vector<RunResult>> RunAll(const BackendRegistry& registry, const std::vector<Run>& runs,
                                      const RunnerOptions& options) {
  if (options.backends.empty()) return Error{"no backends to run"};
  for (const std::string& name : options.backends) {
    if (!registry.Has(name)) {
      return Error{Concat({"unknown backend \"", name, "\" (known: ", KnownBackends(registry), ")"})};
    }
  }
  if (options.jobs < 1) return Error{Concat({"jobs must be >= 1, got ", std::to_string(options.jobs)})};
  if (options.maxSamples < 1) return Error{"maxSamples must be >= 1"};
  if (options.plotPoints < 2) return Error{"plotPoints must be >= 2"};
  if (options.replayFrames < 2) return Error{"replayFrames must be >= 2"};

  // Jobs in output order; each writes only its own slot. Every scenario's
  // list is checked before anything runs.
  struct Job {
    const Run* run;
    std::string backend;
  };
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
  std::vector<RunResult> results(jobs.size());
  std::mutex progressMutex;
  std::size_t done = 0;
  const auto execute = [&](std::size_t index) {
    const auto start = std::chrono::steady_clock::now();
    results[index] = RunOne(registry, *jobs[index].run, jobs[index].backend, options);
    if (options.progress) {
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::lock_guard lock(progressMutex);
      ++done;
      char line[64];
      std::snprintf(line, sizeof line, " %.2f s", seconds);
      options.progress(
          Concat({"[", std::to_string(done), "/", std::to_string(jobs.size()), "] ", jobs[index].run->id, " ",
                  jobs[index].backend, line, results[index].error.empty() ? "" : " (error)"}));
    }
  };

  if (options.jobs == 1) {
    for (std::size_t i = 0; i < jobs.size(); ++i) execute(i);
    return results;
  }
  // Free jobs go to a shared queue; each serial family gets one lane.
  std::vector<std::size_t> freeJobs;
  std::map<std::string, std::vector<std::size_t>> lanes;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const std::string family = SerialFamily(jobs[i].backend);
    if (family.empty()) {
      freeJobs.push_back(i);
    } else {
      lanes[family].push_back(i);
    }
  }
  std::atomic<std::size_t> next{0};
  std::vector<std::thread> threads;
  for (auto& [family, lane] : lanes) {
    threads.emplace_back([&execute, &lane] {
      for (std::size_t index : lane) execute(index);
    });
  }
  const int workers = std::max(1, options.jobs - static_cast<int>(lanes.size()));
  for (int w = 0; w < workers; ++w) {
    threads.emplace_back([&] {
      for (std::size_t k = next++; k < freeJobs.size(); k = next++) execute(freeJobs[k]);
    });
  }
  for (std::thread& thread : threads) thread.join();
  return results;
}

}  // namespace talus::harness
