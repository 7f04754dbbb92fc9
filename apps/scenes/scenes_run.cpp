// The run of talus-scenes (scenes_run.h).
#include "scenes_run.h"

#include <iostream>
#include <optional>

#include "report_writer.h"
#include "scenes_output.h"
#include "talus/harness/scenes/bench_perturb.h"
#include "talus/harness/scenes/bench_scenes.h"

namespace talus::scenes {
namespace {

using harness::BenchScene;

// One (scene, parameter) pair to run on every engine.
struct Job {
  const BenchScene* scene;
  int parameter;
};

// The thread count and solver settings of one series of runs.
struct Setting {
  int threads = 1;
  harness::BenchSolver solver;
};

// Every run's job: the --scene (or every scene), at --param or its default,
// or with --series at each parameter of its series.
std::vector<Job> MakeJobs(const ScenesOptions& options) {
  std::vector<Job> jobs;
  for (const BenchScene& scene : harness::BenchScenes()) {
    if (!options.scene.empty() && scene.name != options.scene) continue;
    if (options.series) {
      for (int parameter : scene.series) jobs.push_back({&scene, parameter});
    } else {
      jobs.push_back({&scene, options.parameter != 0 ? options.parameter : scene.defaultParameter});
    }
  }
  return jobs;
}

// Every (threads, iterations, substeps) setting of one engine, each one
// series of repeats. The Talus worlds step on each of the --threads
// counts; every peer on one.
std::vector<Setting> EngineSettings(const ScenesOptions& options, bool talus) {
  std::vector<Setting> settings;
  for (int threads : talus ? options.threads : std::vector<int>{1}) {
    for (int iterations : options.iterations) {
      for (int substeps : options.substeps) settings.push_back({threads, {iterations, substeps}});
    }
  }
  return settings;
}

// "scene P=n engine", with the thread count and the solver setting where
// the run varies them or departs from the engine's own.
std::string SeriesLabel(const ScenesOptions& options, const Job& job, const std::string& engine, bool talus,
                        const Setting& setting) {
  std::string label = std::string(job.scene->name) + " " + std::string(job.scene->parameterName) + "=" +
                      std::to_string(job.parameter) + " " + engine;
  if (talus && options.threads.size() > 1) label += " threads=" + std::to_string(setting.threads);
  if (options.iterations.size() > 1 || options.substeps.size() > 1 || setting.solver.iterations != 0 ||
      setting.solver.substeps != 1) {
    label += " (" + harness::BenchSolverLabel(setting.solver) + ")";
  }
  return label;
}

// What one series of repeats runs: which job, engine and setting, built
// from which registry, under which label.
struct Series {
  const Job& job;
  const std::string& engine;
  bool talus = false;
  const Setting& setting;
  const harness::BackendRegistry& builder;
  std::string label;
};

// Runs one series' repeats, each one printed line; a run that fails is
// said on stderr and counted in `failures`. The summary of a perturbed
// series goes to stderr. False when stdout could not be written: nothing
// more can be told, so the caller stops rather than run for nothing.
bool RunSeries(const ScenesOptions& options, const Series& s, int& failures) {
  const int repeats = options.repeats.value_or(1);
  std::vector<harness::BenchReport> series;
  for (int repeat = 0; repeat < repeats; ++repeat) {
    std::optional<harness::BenchPerturbation> perturbation;
    if (options.perturb) {
      perturbation = harness::BenchPerturbation{repeat, *options.perturb,
                                                harness::RepeatSeed(options.perturbSeed.value_or(0), repeat)};
    }
    const std::string runLabel = repeats > 1 ? s.label + " repeat " + std::to_string(repeat) : s.label;
    harness::BenchProgress progress;
    if (options.series) {
      std::cerr << runLabel << ": building\n";
      progress = SeriesProgress(runLabel);
    }
    auto report = harness::RunBenchScene(s.builder, s.engine, *s.job.scene, s.job.parameter, options.steps,
                                         progress, perturbation, s.setting.solver);
    if (!report) {
      std::cerr << "talus-scenes: " << runLabel << ": " << report.GetError().message << '\n';
      ++failures;
      continue;
    }
    if (s.talus) report.Value().threads = s.setting.threads;
    if (options.series && !report.Value().skipped.empty()) {
      std::cerr << runLabel << ": skipped: " << report.Value().skipped << '\n';
    }
    if (!PrintReport(report.Value(), options.format == "csv")) return false;
    const bool skipped = !report.Value().skipped.empty();
    series.push_back(std::move(report.Value()));
    if (skipped) break;  // every repeat would be skipped for the same reason
  }
  if (options.perturb && !series.empty() && series.front().skipped.empty()) PrintRepeatSummary(series);
  return true;
}

}  // namespace

int RunScenes(const ScenesOptions& options, const std::vector<std::string>& engines,
              const std::map<int, harness::BackendRegistry>& registries) {
  const harness::BackendRegistry& registry = registries.begin()->second;
  const std::vector<Job> jobs = MakeJobs(options);
  if (options.format == "csv" && !PrintLine(CsvHeader(options.perturb.has_value()))) return 1;
  int failures = 0;
  for (const Job& job : jobs) {
    for (const std::string& engine : engines) {
      const bool talus = engine.starts_with("talus");
      for (const Setting& setting : EngineSettings(options, talus)) {
        const Series series{.job = job,
                            .engine = engine,
                            .talus = talus,
                            .setting = setting,
                            .builder = talus ? registries.at(setting.threads) : registry,
                            .label = SeriesLabel(options, job, engine, talus, setting)};
        if (!RunSeries(options, series, failures)) return 1;
      }
    }
  }
  return failures == 0 ? 0 : 1;
}

}  // namespace talus::scenes
