// `talus-testbed sweep`: every scenario with a truth at every (time step,
// iterations) pair through every backend, then the run-time-against-error
// analysis (harness sweep.h); `--shard i/n` runs one part of the job list
// into a shard file that `merge` combines.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <thread>

#include "sweep_commands.h"
#include "talus/harness/run/results_file.h"
#include "talus/harness/run/runner.h"
#include "talus/harness/scenario/scenario_limits.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/harness/support/atomic_file.h"
#include "talus/harness/sweep/perturbed_copies.h"
#include "talus/harness/sweep/sweep.h"
#include "talus/reference/all_backends.h"
#include "testbed_commands.h"
#include "testbed_flags.h"

namespace talus::testbed {
namespace {

namespace fs = std::filesystem;

struct SweepOptions {
  std::vector<std::string> scenarios;
  std::vector<std::string> backends;
  std::vector<double> timeSteps{1.0 / 30, 1.0 / 60, 1.0 / 120, 1.0 / 240, 1.0 / 480, 1.0 / 960};
  std::vector<int> iterations{5, 10, 20, 40};
  std::string shard;
  std::string out = "reports/sweep";
  int jobs = 0;
  int perturbCopies = harness::kDefaultPerturbCopies;
  double perturbation = harness::kDefaultSweepPerturbation;
  bool deterministic = false;
  bool quiet = false;
};

int Sweep(const SweepOptions& options) {
  // Checked before anything runs; the amount only matters with copies.
  std::optional<std::string> problem = harness::PerturbCopiesProblem(options.perturbCopies);
  if (!problem && options.perturbCopies > 0)
    problem = harness::SweepPerturbationProblem(options.perturbation);
  if (problem) {
    std::cerr << "talus-testbed: sweep: " << *problem << "\n";
    return kExitBadInput;
  }
  harness::Shard shard;
  if (!options.shard.empty()) {
    auto parsed = harness::ParseShard(options.shard);
    if (!parsed) {
      std::cerr << "talus-testbed: " << parsed.GetError().message << "\n";
      return kExitBadInput;
    }
    shard = parsed.Value();
  }
  std::vector<fs::path> paths(options.scenarios.begin(), options.scenarios.end());
  if (paths.empty())
    paths.push_back(fs::exists("scenarios") ? fs::path("scenarios") : fs::path(TALUS_DEFAULT_SCENARIOS));
  auto loaded = harness::LoadScenarios(paths);
  if (!loaded) {
    std::cerr << "talus-testbed: " << loaded.GetError().message << "\n";
    return kExitBadInput;
  }
  std::vector<harness::Run> withTruth;
  for (const harness::Run& run : loaded.Value()) {
    if (!run.scenario.truths.empty()) withTruth.push_back(run);
  }
  auto expanded = harness::ExpandStepping(withTruth, options.timeSteps, options.iterations);
  if (!expanded) {
    std::cerr << "talus-testbed: " << expanded.GetError().message << "\n";
    return kExitBadInput;
  }
  const std::vector<harness::Run>& all = expanded.Value();
  harness::ShardFile part;
  part.shard = shard;
  part.runCount = static_cast<int>(all.size());
  part.runIndices = harness::ShardRuns(part.runCount, shard);
  part.identity = harness::MakeShardIdentity(all, options.timeSteps, options.iterations);
  part.identity.perturbCopies = options.perturbCopies;
  part.identity.perturbation = options.perturbCopies > 0 ? options.perturbation : 0.0;
  std::vector<harness::Run> runs;
  for (int r : part.runIndices) runs.push_back(all[static_cast<std::size_t>(r)]);
  auto withCopies = harness::WithPerturbedCopies(runs, options.perturbCopies, options.perturbation);
  if (!withCopies) {
    std::cerr << "talus-testbed: " << withCopies.GetError().message << "\n";
    return kExitBadInput;
  }

  harness::RunnerOptions runner;
  runner.backends = options.backends.empty() ? DefaultBackends() : options.backends;
  runner.jobs =
      options.jobs > 0 ? options.jobs : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  runner.deterministic = options.deterministic;
  runner.plotPoints = 2;  // a sweep's report shows costs and errors, not time series
  if (!options.quiet) runner.progress = [](const std::string& line) { std::cerr << line << "\n"; };
  runner.notice = [](const std::string& line) { std::cout << "talus-testbed: " << line << "\n"; };
  auto results = harness::RunAll(reference::AllBackends(), withCopies.Value(), runner);
  if (!results) {
    std::cerr << "talus-testbed: " << results.GetError().message << "\n";
    return kExitBadInput;
  }
  for (const harness::Run& run : runs) {
    // RunAll accepted every list, so this cannot fail here.
    auto chosen = harness::BackendsForRun(reference::AllBackends(), run, runner.backends);
    part.resultCounts.push_back(chosen ? static_cast<int>(chosen.Value().size()) : 0);
  }
  part.results.backends = runner.backends;
  part.results.deterministic = options.deterministic;
  auto folded = harness::FoldPerturbedCopies(std::move(results).Value(), part.resultCounts,
                                             options.perturbCopies, options.perturbation);
  if (!folded) {
    std::cerr << "talus-testbed: " << folded.GetError().message << "\n";
    return kExitBadInput;
  }
  part.results.results = std::move(folded).Value();
  const fs::path out(options.out);
  if (!options.shard.empty()) {
    const fs::path path =
        out / ("shard-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count) + ".json");
    if (!WriteText(path, harness::ShardToJson(part))) return kExitBadInput;
    std::cout << "shard " << options.shard << ": " << part.runIndices.size() << " of " << part.runCount
              << " runs x " << runner.backends.size() << " backends\nshard file: " << path.string() << "\n";
    return kExitOk;
  }
  const std::vector<harness::SweepGroup> groups =
      harness::AnalyseSweep(part.results, harness::kSweepSingleSetting);
  const std::string markdown = harness::SweepMarkdown(groups);
  std::vector<harness::FileText> files = harness::ResultsFileTexts(out / "results.json", part.results);
  files.push_back({out / "sweep.json", harness::SweepToJson(groups)});
  files.push_back({out / "sweep.md", markdown});
  if (!WriteTexts(files)) return kExitBadInput;
  std::cout << markdown << "\nresults: " << (out / "results.json").string()
            << " (talus-testbed report draws the charts)\nsweep: " << (out / "sweep.json").string() << ", "
            << (out / "sweep.md").string() << "\n";
  return kExitOk;
}

}  // namespace

bool WriteText(const fs::path& path, const std::string& text) { return WriteTexts({{path, text}}); }

bool WriteTexts(const std::vector<harness::FileText>& files) {
  for (const harness::FileText& file : files) {
    // A folder that cannot be made shows as the file's own error below.
    std::error_code ignored;
    if (!file.path.parent_path().empty()) fs::create_directories(file.path.parent_path(), ignored);
  }
  auto written = harness::WriteFilesAtomically(files);
  if (!written) std::cerr << "talus-testbed: " << written.GetError().message << "\n";
  return static_cast<bool>(written);
}

void AddSweepCommand(CLI::App& app, CommandAction& chosen) {
  auto options = std::make_shared<SweepOptions>();
  CLI::App* command = app.add_subcommand(
      "sweep", "run time against error: scenarios with a truth over time steps and iterations");
  command->add_option("scenarios", options->scenarios, "scenario files or folders (default: scenarios/)");
  command->add_option("-b,--backend", options->backends, "backends (default: all)")->delimiter(',');
  command->add_option("--time-step", options->timeSteps, "time steps, s")
      ->delimiter(',')
      ->check(kTimeStepRange)
      ->capture_default_str();
  command->add_option("--iterations", options->iterations, "solver iterations (0 = engine default)")
      ->delimiter(',')
      ->check(kIterationsRange)
      ->capture_default_str();
  command->add_option("--shard", options->shard, "run only shard i of n (i/n), into a shard file for merge");
  command->add_option("-o,--out", options->out, "output folder")->capture_default_str();
  command->add_option("-j,--jobs", options->jobs, "threads (0 = every core)")->check(kJobsRange);
  command
      ->add_option(
          "--perturb-copies", options->perturbCopies,
          "perturbed copies per sweep point (initial positions moved by round-off): the error's noise "
          "floor and the median cost; 0 = none, the exact comparison")
      ->capture_default_str();
  command
      ->add_option("--perturb", options->perturbation,
                   "m: each dynamic body's initial coordinates move by at most this in a copy")
      ->capture_default_str();
  command->add_flag("--deterministic", options->deterministic, "zero wall times (costs become 0)");
  command->add_flag("-q,--quiet", options->quiet, "no progress on stderr");
  command->callback([options, &chosen] { chosen = [options] { return Sweep(*options); }; });
}

}  // namespace talus::testbed
