// talus-scenes: runs the reference benchmark scenes (pyramid, hull_pile;
// docs/bench-scenes.md) through Talus and its peers in one invocation and
// prints one machine-readable line per scene, parameter and engine, so that
// speed ratios are taken on the same machine at the same moment.
//
//   talus-scenes --scene pyramid --param 15 --engines bullet,ode-quickstep
//   talus-scenes --series --format jsonl      (every scene's scaling series)
//   talus-scenes --scene pyramid --param 20 --engines talus-coloured --threads 1,2
//   talus-scenes --scene pyramid --engines talus,bullet --perturb 1e-9 --repeats 10
//       (each repeat from initial positions moved by up to 1e-9 m; the spread
//       and whether the verdict held in every repeat go to stderr)
//   talus-scenes --scene pyramid --param 10 --iterations 0,4,8,16 --substeps 1,2
//       (one line per engine, iteration count and substep count: total time
//       against drift or penetration over each engine's settings)
//
// The cost of a run is its total wall time (and the mean step, total /
// steps), with the longest step beside it; never a median over the steps of
// one run (docs/bench-scenes.md, "Cost").
// With a list of thread counts each Talus engine runs once per count, one
// right after the other, so the speed-ups compare runs minutes apart; every
// peer runs once, on one thread.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "flag_range.h"
#include "report_writer.h"
#include "talus/harness/scenes/bench_perturb.h"
#include "talus/harness/scenes/bench_run.h"
#include "talus/harness/scenes/bench_scenes.h"
#include "talus/reference/all_backends.h"
#include "talus/world_settings.h"

namespace {

using talus::harness::BenchScene;

struct Options {
  std::string scene;
  int parameter = 0;  // 0: the scene's default
  std::string engines;
  int steps = talus::harness::kBenchDefaultSteps;
  std::string format = "csv";
  bool series = false;
  std::vector<int> threads = {1};            // WorldSettings::threads of the Talus backends, one run each
  std::optional<double> perturb;             // metres; absent: unperturbed
  std::optional<int> repeats;                // absent: 1
  std::optional<std::uint64_t> perturbSeed;  // absent: 0
  std::vector<int> iterations = {0};         // Run::iterations per run; 0: the engine's default
  std::vector<int> substeps = {1};           // backend steps of h / N per scene step
};

std::vector<std::string> SplitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

// A count the list names more than once, or nothing.
std::optional<int> RepeatedCount(const std::vector<int>& counts) {
  for (std::size_t i = 0; i < counts.size(); ++i) {
    if (std::find(counts.begin(), counts.begin() + static_cast<std::ptrdiff_t>(i), counts[i]) !=
        counts.begin() + static_cast<std::ptrdiff_t>(i)) {
      return counts[i];
    }
  }
  return std::nullopt;
}

// The thread count and solver settings of one series of runs.
struct Setting {
  int threads = 1;
  talus::harness::BenchSolver solver;
};

// Writes one line to stdout and pushes it out at once (a series runs for
// minutes and each line is a finished result). False, after saying why on
// stderr, when stdout cannot take it (a full disk, a file that is a
// directory): the output would be incomplete, so the program stops.
bool PrintLine(const std::string& line) {
  errno = 0;
  std::cout << line << '\n' << std::flush;
  if (std::cout) return true;
  std::cerr << "talus-scenes: stdout: cannot write (" << (errno != 0 ? std::strerror(errno) : "write failed")
            << ")\n";
  return false;
}

// One (scene, parameter) pair to run on every engine.
struct Job {
  const BenchScene* scene;
  int parameter;
};

}  // namespace

int main(int argc, char** argv) {
  namespace harness = talus::harness;
  using talus::flags::InRange;
  Options options;
  CLI::App app{"talus-scenes: the reference benchmark scenes (pyramid, hull_pile) on every engine"};
  app.add_option("--scene", options.scene, "pyramid or hull_pile (with --series: only that scene's series)")
      ->check(CLI::IsMember({"pyramid", "hull_pile"}));
  // 0 is "not given" inside the program, so a given 0 (or a negative) is refused by the range;
  // each scene checks its own range again when it is built (bench_scenes.h).
  app.add_option("--param", options.parameter, "H for pyramid (default 15), L for hull_pile (default 10)")
      ->check(InRange(std::min(harness::kPyramidMinHeight, harness::kHullPileMinSide),
                      std::max(harness::kPyramidMaxHeight, harness::kHullPileMaxSide)));
  app.add_option("--engines", options.engines, "comma-separated backends (default: every registered one)");
  app.add_option("--steps", options.steps, "steps per run")->check(InRange(1, 1000000));
  app.add_option("--format", options.format, "csv or jsonl")->check(CLI::IsMember({"csv", "jsonl"}));
  app.add_flag("--series", options.series,
               "run the scaling series (pyramid H = 10, 15, 20, 30; hull_pile L = 10, 20, 40); progress on "
               "stderr");
  app.add_option("--threads", options.threads,
                 "comma-separated thread counts of the Talus backends' worlds (WorldSettings::threads), "
                 "each Talus engine run once per count; peers run once, on one thread")
      ->delimiter(',')
      ->check(InRange(1, talus::kMaxThreads));
  app.add_option(
      "--perturb", options.perturb,
      "move every dynamic body's initial position by a seeded uniform offset in [-A, A) m per axis "
      "(0 <= A <= 1e-3)");
  app.add_option(
      "--repeats", options.repeats,
      "with --perturb: runs per scene and engine, repeat r seeded with --perturb-seed + r (1 to 1000)");
  app.add_option("--perturb-seed", options.perturbSeed,
                 "with --perturb: the first repeat's SplitMix64 seed (default 0)")
      ->check(InRange<std::uint64_t>(0, std::numeric_limits<std::uint64_t>::max()));
  app.add_option(
         "--iterations", options.iterations,
         "comma-separated solver iteration counts, one run each (0: the engine's default, else 1 to " +
             std::to_string(talus::harness::kBenchMaxIterations) +
             "): Talus's velocity and position iterations, Bullet's solver iterations, ODE "
             "quickstep's iterations per step, MuJoCo's iterations; refused for ode-step, "
             "which has none")
      ->delimiter(',');
  app.add_option("--substeps", options.substeps,
                 "comma-separated substep counts, one run each (1 to " +
                     std::to_string(talus::harness::kBenchMaxSubsteps) +
                     "): every engine takes N steps of h / N per scene step, timed as one")
      ->delimiter(',');
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // --help exits 0; a refused argument exits 2, as every other bad input here does.
    return app.exit(error) == 0 ? 0 : 2;
  }

  if (!options.perturb && (options.repeats || options.perturbSeed)) {
    std::cerr
        << "talus-scenes: --repeats and --perturb-seed need --perturb (unperturbed repeats give the same "
           "figures; use --perturb 0 to repeat on purpose)\n";
    return 2;
  }
  if (options.perturb) {
    if (auto problem = talus::harness::PositionPerturbationProblem(*options.perturb)) {
      std::cerr << "talus-scenes: --perturb: " << *problem << '\n';
      return 2;
    }
  }
  const int repeats = options.repeats.value_or(1);
  if (auto problem = talus::harness::BenchRepeatsProblem(repeats)) {
    std::cerr << "talus-scenes: --repeats: " << *problem << '\n';
    return 2;
  }
  for (const auto& [flag, counts] :
       {std::pair<const char*, const std::vector<int>*>{"--threads", &options.threads},
        {"--iterations", &options.iterations},
        {"--substeps", &options.substeps}}) {
    if (const auto repeat = RepeatedCount(*counts)) {
      std::cerr << "talus-scenes: " << flag << " names " << *repeat << " twice\n";
      return 2;
    }
  }
  // One registry per thread count: a Talus backend's worlds take their
  // thread count from the registry that builds them.
  std::map<int, talus::harness::BackendRegistry> registries;
  for (int threads : options.threads) registries.emplace(threads, talus::reference::MakeAllBackends(threads));
  const talus::harness::BackendRegistry& registry = registries.begin()->second;

  if (!options.series && options.scene.empty()) {
    std::cerr << "talus-scenes: --scene is required unless --series is given\n";
    return 2;
  }
  if (options.series && options.parameter != 0) {
    std::cerr << "talus-scenes: --param and --series exclude each other\n";
    return 2;
  }
  std::vector<std::string> engines = options.engines.empty() ? registry.Names() : SplitList(options.engines);
  if (engines.empty()) {
    std::cerr << "talus-scenes: --engines \"" << options.engines << "\" names no engine\n";
    return 2;
  }
  for (const std::string& engine : engines) {
    if (!registry.Has(engine)) {
      std::cerr << "talus-scenes: --engines: unknown engine \"" << engine << "\"; known:";
      for (const std::string& name : registry.Names()) std::cerr << ' ' << name;
      std::cerr << '\n';
      return 2;
    }
  }
  // Every setting checked before anything runs, so a bad one is refused
  // whole, not after minutes of other runs: the ranges first, then whether
  // each engine has the knob.
  for (int iterations : options.iterations) {
    if (auto problem = talus::harness::BenchSolverProblem("", {iterations, 1})) {
      std::cerr << "talus-scenes: --iterations: " << *problem << '\n';
      return 2;
    }
    for (const std::string& engine : engines) {
      if (auto problem = talus::harness::BenchSolverProblem(engine, {iterations, 1})) {
        std::cerr << "talus-scenes: --iterations: " << *problem << '\n';
        return 2;
      }
    }
  }
  for (int substeps : options.substeps) {
    if (auto problem = talus::harness::BenchSolverProblem("", {0, substeps})) {
      std::cerr << "talus-scenes: --substeps: " << *problem << '\n';
      return 2;
    }
  }

  std::vector<Job> jobs;
  for (const BenchScene& scene : talus::harness::BenchScenes()) {
    if (!options.scene.empty() && scene.name != options.scene) continue;
    if (options.series) {
      for (int parameter : scene.series) jobs.push_back({&scene, parameter});
    } else {
      jobs.push_back({&scene, options.parameter != 0 ? options.parameter : scene.defaultParameter});
    }
  }

  const bool csv = options.format == "csv";
  if (csv && !PrintLine(talus::scenes::CsvHeader(options.perturb.has_value()))) return 1;
  int failures = 0;
  for (const Job& job : jobs) {
    for (const std::string& engine : engines) {
      // The Talus worlds step on each of the --threads counts; every peer on one.
      const bool talus = engine.starts_with("talus");
      // Every (threads, iterations, substeps) setting is one series of repeats.
      std::vector<Setting> settings;
      for (int threads : talus ? options.threads : std::vector<int>{1}) {
        for (int iterations : options.iterations) {
          for (int substeps : options.substeps) settings.push_back({threads, {iterations, substeps}});
        }
      }
      for (const Setting& setting : settings) {
        const int threads = setting.threads;
        std::string label = std::string(job.scene->name) + " " + std::string(job.scene->parameterName) + "=" +
                            std::to_string(job.parameter) + " " + engine;
        if (talus && options.threads.size() > 1) label += " threads=" + std::to_string(threads);
        if (options.iterations.size() > 1 || options.substeps.size() > 1 || setting.solver.iterations != 0 ||
            setting.solver.substeps != 1) {
          label += " (" + talus::harness::BenchSolverLabel(setting.solver) + ")";
        }
        const talus::harness::BackendRegistry& builder = talus ? registries.at(threads) : registry;
        std::vector<talus::harness::BenchReport> series;
        for (int repeat = 0; repeat < repeats; ++repeat) {
          std::optional<talus::harness::BenchPerturbation> perturbation;
          if (options.perturb) {
            perturbation = talus::harness::BenchPerturbation{
                repeat, *options.perturb,
                talus::harness::RepeatSeed(options.perturbSeed.value_or(0), repeat)};
          }
          const std::string runLabel = repeats > 1 ? label + " repeat " + std::to_string(repeat) : label;
          talus::harness::BenchProgress progress;
          if (options.series) {
            std::cerr << runLabel << ": building\n";
            progress = [&runLabel](int step, int steps) {
              if (step % 100 == 0 || step == steps)
                std::cerr << runLabel << ": step " << step << "/" << steps << '\n';
            };
          }
          auto report = talus::harness::RunBenchScene(builder, engine, *job.scene, job.parameter,
                                                      options.steps, progress, perturbation, setting.solver);
          if (!report) {
            std::cerr << "talus-scenes: " << runLabel << ": " << report.GetError().message << '\n';
            ++failures;
            continue;
          }
          if (talus) report.Value().threads = threads;
          if (options.series && !report.Value().skipped.empty()) {
            std::cerr << runLabel << ": skipped: " << report.Value().skipped << '\n';
          }
          if (!PrintLine(csv ? talus::scenes::FormatCsv(report.Value())
                             : talus::scenes::FormatJson(report.Value()))) {
            return 1;  // nothing more can be told: stop rather than run for nothing
          }
          const bool skipped = !report.Value().skipped.empty();
          series.push_back(std::move(report.Value()));
          if (skipped) break;  // every repeat would be skipped for the same reason
        }
        if (options.perturb && !series.empty() && series.front().skipped.empty()) {
          auto summary = talus::harness::SummarizeRepeats(series);
          if (summary)
            std::cerr << talus::harness::FormatRepeatSummary(series.front(), summary.Value()) << '\n';
        }
      }
    }
  }
  return failures == 0 ? 0 : 1;
}
