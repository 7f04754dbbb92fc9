// talus-scenes: runs the reference benchmark scenes (pyramid, hull_pile;
// docs/bench-scenes.md) through Talus and its peers in one invocation and
// prints one machine-readable line per scene, parameter and engine, so that
// speed ratios are taken on the same machine at the same moment.
//
//   talus-scenes --scene pyramid --param 15 --engines bullet,ode-quickstep
//   talus-scenes --series --format jsonl      (every scene's scaling series)
//   talus-scenes --scene pyramid --param 20 --engines talus-coloured --threads 1,2
//
// With a list of thread counts each Talus engine runs once per count, one
// right after the other, so the speed-ups compare runs minutes apart; every
// peer runs once, on one thread.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "report_writer.h"
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
  std::vector<int> threads = {1};  // WorldSettings::threads of the Talus backends, one run each
};

std::vector<std::string> SplitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

// A thread count the list names more than once, or nothing.
std::optional<int> RepeatedCount(const std::vector<int>& counts) {
  for (std::size_t i = 0; i < counts.size(); ++i) {
    if (std::find(counts.begin(), counts.begin() + static_cast<std::ptrdiff_t>(i), counts[i]) !=
        counts.begin() + static_cast<std::ptrdiff_t>(i)) {
      return counts[i];
    }
  }
  return std::nullopt;
}

// One (scene, parameter) pair to run on every engine.
struct Job {
  const BenchScene* scene;
  int parameter;
};

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App app{"talus-scenes: the reference benchmark scenes (pyramid, hull_pile) on every engine"};
  app.add_option("--scene", options.scene, "pyramid or hull_pile (with --series: only that scene's series)")
      ->check(CLI::IsMember({"pyramid", "hull_pile"}));
  // 0 is "not given" inside the program, so a given 0 (or a negative) is refused by the range.
  app.add_option("--param", options.parameter, "H for pyramid (default 15), L for hull_pile (default 10)")
      ->check(CLI::PositiveNumber);
  app.add_option("--engines", options.engines, "comma-separated backends (default: every registered one)");
  app.add_option("--steps", options.steps, "steps per run")->check(CLI::Range(1, 1000000));
  app.add_option("--format", options.format, "csv or jsonl")->check(CLI::IsMember({"csv", "jsonl"}));
  app.add_flag("--series", options.series,
               "run the scaling series (pyramid H = 10, 15, 20, 30; hull_pile L = 10, 20, 40); progress on "
               "stderr");
  app.add_option("--threads", options.threads,
                 "comma-separated thread counts of the Talus backends' worlds (WorldSettings::threads), "
                 "each Talus engine run once per count; peers run once, on one thread")
      ->delimiter(',')
      ->check(CLI::Range(1, talus::kMaxThreads));
  CLI11_PARSE(app, argc, argv);

  if (const auto repeat = RepeatedCount(options.threads)) {
    std::cerr << "talus-scenes: --threads names " << *repeat << " twice\n";
    return 2;
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
  if (csv) std::cout << talus::scenes::CsvHeader() << '\n' << std::flush;
  int failures = 0;
  for (const Job& job : jobs) {
    for (const std::string& engine : engines) {
      // The Talus worlds step on each of the --threads counts; every peer on one.
      const bool talus = engine.starts_with("talus");
      for (int threads : talus ? options.threads : std::vector<int>{1}) {
        std::string label = std::string(job.scene->name) + " " + std::string(job.scene->parameterName) + "=" +
                            std::to_string(job.parameter) + " " + engine;
        if (talus && options.threads.size() > 1) label += " threads=" + std::to_string(threads);
        talus::harness::BenchProgress progress;
        if (options.series) {
          std::cerr << label << ": building\n";
          progress = [&label](int step, int steps) {
            if (step % 100 == 0 || step == steps)
              std::cerr << label << ": step " << step << "/" << steps << '\n';
          };
        }
        const talus::harness::BackendRegistry& builder = talus ? registries.at(threads) : registry;
        auto report = talus::harness::RunBenchScene(builder, engine, *job.scene, job.parameter, options.steps,
                                                    progress);
        if (!report) {
          std::cerr << "talus-scenes: " << label << ": " << report.GetError().message << '\n';
          ++failures;
          continue;
        }
        if (talus) report.Value().threads = threads;
        if (options.series && !report.Value().skipped.empty()) {
          std::cerr << label << ": skipped: " << report.Value().skipped << '\n';
        }
        std::cout << (csv ? talus::scenes::FormatCsv(report.Value())
                          : talus::scenes::FormatJson(report.Value()))
                  << '\n'
                  << std::flush;
      }
    }
  }
  return failures == 0 ? 0 : 1;
}
