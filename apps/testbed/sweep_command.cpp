// `talus-testbed sweep`: every scenario with a truth at every (time step,
// iterations) pair through every backend, then the run-time-against-error
// analysis (harness sweep_analysis.h); `--shard i/n` runs one part of the job list
// into a shard file that `merge` combines.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>
#include <variant>

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

// The noise floor's settings, checked before anything runs (the amount
// only matters with copies); false after saying what is wrong.
bool PerturbationAccepted(const SweepOptions& options) {
  std::optional<std::string> problem = harness::PerturbCopiesProblem(options.perturbCopies);
  if (!problem && options.perturbCopies > 0)
    problem = harness::SweepPerturbationProblem(options.perturbation);
  if (problem) std::cerr << "talus-testbed: sweep: " << *problem << "\n";
  return !problem;
}

// The shard asked for: the whole list (shard 0 of 1) without --shard.
Result<harness::Shard> ChosenShard(const SweepOptions& options) {
  if (options.shard.empty()) return harness::Shard{};
  return harness::ParseShard(options.shard);
}

// Every scenario with a truth (the folder scenarios/ by default) at every
// (time step, iterations) pair: the unsharded run list.
Result<std::vector<harness::Run>> SteppedRuns(const SweepOptions& options) {
  std::vector<fs::path> paths(options.scenarios.begin(), options.scenarios.end());
  if (paths.empty())
    paths.push_back(fs::exists("scenarios") ? fs::path("scenarios") : fs::path(TALUS_DEFAULT_SCENARIOS));
  auto loaded = harness::LoadScenarios(paths);
  if (!loaded) return loaded.GetError();
  std::vector<harness::Run> withTruth;
  for (const harness::Run& run : loaded.Value()) {
    if (!run.scenario.truths.empty()) withTruth.push_back(run);
  }
  return harness::ExpandStepping(withTruth, options.timeSteps, options.iterations);
}

// The shard's place in the partition and the identity every shard of it
// shares; its results come later.
harness::ShardFile PlanShard(const std::vector<harness::Run>& all, harness::Shard shard,
                             const SweepOptions& options) {
  harness::ShardFile part;
  part.shard = shard;
  part.runCount = static_cast<int>(all.size());
  part.runIndices = harness::ShardRuns(part.runCount, shard);
  part.identity = harness::MakeShardIdentity(all, options.timeSteps, options.iterations);
  part.identity.perturbCopies = options.perturbCopies;
  part.identity.perturbation = options.perturbCopies > 0 ? options.perturbation : 0.0;
  return part;
}

harness::RunnerOptions SweepRunnerOptions(const SweepOptions& options) {
  harness::RunnerOptions runner;
  runner.backends = options.backends.empty() ? DefaultBackends() : options.backends;
  runner.jobs =
      options.jobs > 0 ? options.jobs : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  runner.deterministic = options.deterministic;
  runner.plotPoints = 2;  // a sweep's report shows costs and errors, not time series
  if (!options.quiet) runner.progress = [](const std::string& line) { std::cerr << line << "\n"; };
  runner.notice = [](const std::string& line) { std::cout << "talus-testbed: " << line << "\n"; };
  return runner;
}

// Runs the shard's runs with their perturbed copies through the backends
// and folds the copies back into one result per point, into `part`.
Result<std::monostate> RunShard(const std::vector<harness::Run>& all, const SweepOptions& options,
                                const harness::RunnerOptions& runner, harness::ShardFile& part) {
  std::vector<harness::Run> runs;
  for (int r : part.runIndices) runs.push_back(all[static_cast<std::size_t>(r)]);
  auto withCopies = harness::WithPerturbedCopies(runs, options.perturbCopies, options.perturbation);
  if (!withCopies) return withCopies.GetError();
  auto results = harness::RunAll(reference::AllBackends(), withCopies.Value(), runner);
  if (!results) return results.GetError();
  for (const harness::Run& run : runs) {
    // RunAll accepted every list, so this cannot fail here.
    auto chosen = harness::BackendsForRun(reference::AllBackends(), run, runner.backends);
    part.resultCounts.push_back(chosen ? static_cast<int>(chosen.Value().size()) : 0);
  }
  part.results.backends = runner.backends;
  part.results.deterministic = options.deterministic;
  auto folded = harness::FoldPerturbedCopies(std::move(results).Value(), part.resultCounts,
                                             options.perturbCopies, options.perturbation);
  if (!folded) return folded.GetError();
  part.results.results = std::move(folded).Value();
  return std::monostate{};
}

// One shard of a sharded sweep: its file, for `merge`.
int WriteShardFile(const harness::ShardFile& part, const SweepOptions& options) {
  const fs::path path = fs::path(options.out) / ("shard-" + std::to_string(part.shard.index) + "-of-" +
                                                 std::to_string(part.shard.count) + ".json");
  if (!WriteText(path, harness::ShardToJson(part))) return kExitBadInput;
  std::cout << "shard " << options.shard << ": " << part.runIndices.size() << " of " << part.runCount
            << " runs x " << part.results.backends.size() << " backends\nshard file: " << path.string()
            << "\n";
  return kExitOk;
}

// The whole sweep: its results, the analysis as sweep.json and sweep.md,
// the Markdown also on stdout.
int WriteSweepFiles(const harness::ResultsFile& results, const fs::path& out) {
  const std::vector<harness::SweepGroup> groups =
      harness::AnalyseSweep(results, harness::kSweepSingleSetting);
  const std::string markdown = harness::SweepMarkdown(groups);
  std::vector<harness::FileText> files = harness::ResultsFileTexts(out / "results.json", results);
  files.push_back({out / "sweep.json", harness::SweepToJson(groups)});
  files.push_back({out / "sweep.md", markdown});
  if (!WriteTexts(files)) return kExitBadInput;
  std::cout << markdown << "\nresults: " << (out / "results.json").string()
            << " (talus-testbed report draws the charts)\nsweep: " << (out / "sweep.json").string() << ", "
            << (out / "sweep.md").string() << "\n";
  return kExitOk;
}

int Sweep(const SweepOptions& options) {
  if (!PerturbationAccepted(options)) return kExitBadInput;
  const auto failed = [](const Error& error) {
    std::cerr << "talus-testbed: " << error.message << "\n";
    return kExitBadInput;
  };
  auto shard = ChosenShard(options);
  if (!shard) return failed(shard.GetError());
  auto all = SteppedRuns(options);
  if (!all) return failed(all.GetError());
  harness::ShardFile part = PlanShard(all.Value(), shard.Value(), options);
  const harness::RunnerOptions runner = SweepRunnerOptions(options);
  if (auto ran = RunShard(all.Value(), options, runner, part); !ran) return failed(ran.GetError());
  if (!options.shard.empty()) return WriteShardFile(part, options);
  return WriteSweepFiles(part.results, fs::path(options.out));
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
