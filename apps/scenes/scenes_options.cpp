// talus-scenes's command line (scenes_options.h).
#include "scenes_options.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>
#include <limits>
#include <sstream>
#include <utility>

#include "flag_range.h"
#include "talus/harness/scenes/bench_perturb.h"
#include "talus/harness/scenes/bench_scenes.h"
#include "talus/world_settings.h"

namespace talus::scenes {
namespace {

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

// Every setting checked before anything runs, so a bad one is refused
// whole, not after minutes of other runs: the ranges first, then whether
// each engine has the knob. Says why on stderr; false when refused.
bool CheckSolverCounts(const ScenesOptions& options, const std::vector<std::string>& engines) {
  for (int iterations : options.iterations) {
    if (auto problem = harness::BenchSolverProblem("", {iterations, 1})) {
      std::cerr << "talus-scenes: --iterations: " << *problem << '\n';
      return false;
    }
    for (const std::string& engine : engines) {
      if (auto problem = harness::BenchSolverProblem(engine, {iterations, 1})) {
        std::cerr << "talus-scenes: --iterations: " << *problem << '\n';
        return false;
      }
    }
  }
  for (int substeps : options.substeps) {
    if (auto problem = harness::BenchSolverProblem("", {0, substeps})) {
      std::cerr << "talus-scenes: --substeps: " << *problem << '\n';
      return false;
    }
  }
  return true;
}

}  // namespace

std::optional<int> ParseScenesOptions(int argc, char** argv, ScenesOptions& options) {
  using flags::InRange;
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
      ->check(InRange(1, kMaxThreads));
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
             std::to_string(harness::kBenchMaxIterations) +
             "): Talus's velocity and position iterations, Bullet's solver iterations, ODE "
             "quickstep's iterations per step, MuJoCo's iterations; refused for ode-step, "
             "which has none")
      ->delimiter(',');
  app.add_option("--substeps", options.substeps,
                 "comma-separated substep counts, one run each (1 to " +
                     std::to_string(harness::kBenchMaxSubsteps) +
                     "): every engine takes N steps of h / N per scene step, timed as one")
      ->delimiter(',');
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // --help exits 0; a refused argument exits 2, as every other bad input here does.
    return app.exit(error) == 0 ? 0 : kExitUsage;
  }
  return std::nullopt;
}

bool CheckFlagCombinations(const ScenesOptions& options) {
  if (!options.perturb && (options.repeats || options.perturbSeed)) {
    std::cerr
        << "talus-scenes: --repeats and --perturb-seed need --perturb (unperturbed repeats give the same "
           "figures; use --perturb 0 to repeat on purpose)\n";
    return false;
  }
  if (options.perturb) {
    if (auto problem = harness::PositionPerturbationProblem(*options.perturb)) {
      std::cerr << "talus-scenes: --perturb: " << *problem << '\n';
      return false;
    }
  }
  if (auto problem = harness::BenchRepeatsProblem(options.repeats.value_or(1))) {
    std::cerr << "talus-scenes: --repeats: " << *problem << '\n';
    return false;
  }
  for (const auto& [flag, counts] :
       {std::pair<const char*, const std::vector<int>*>{"--threads", &options.threads},
        {"--iterations", &options.iterations},
        {"--substeps", &options.substeps}}) {
    if (const auto repeat = RepeatedCount(*counts)) {
      std::cerr << "talus-scenes: " << flag << " names " << *repeat << " twice\n";
      return false;
    }
  }
  if (!options.series && options.scene.empty()) {
    std::cerr << "talus-scenes: --scene is required unless --series is given\n";
    return false;
  }
  if (options.series && options.parameter != 0) {
    std::cerr << "talus-scenes: --param and --series exclude each other\n";
    return false;
  }
  return true;
}

std::optional<std::vector<std::string>> CheckedEngines(const ScenesOptions& options,
                                                       const harness::BackendRegistry& registry) {
  std::vector<std::string> engines = options.engines.empty() ? registry.Names() : SplitList(options.engines);
  if (engines.empty()) {
    std::cerr << "talus-scenes: --engines \"" << options.engines << "\" names no engine\n";
    return std::nullopt;
  }
  for (const std::string& engine : engines) {
    if (!registry.Has(engine)) {
      std::cerr << "talus-scenes: --engines: unknown engine \"" << engine << "\"; known:";
      for (const std::string& name : registry.Names()) std::cerr << ' ' << name;
      std::cerr << '\n';
      return std::nullopt;
    }
  }
  if (!CheckSolverCounts(options, engines)) return std::nullopt;
  return engines;
}

}  // namespace talus::scenes
