// talus-scenes's command line: the options, their parsing (CLI11) and the
// checks of what CLI11 cannot check alone (flags that need each other,
// repeated counts, engines and each engine's solver knobs), all before
// anything runs, so a bad invocation is refused whole with exit status 2.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "talus/harness/backend/backend.h"
#include "talus/harness/scenes/bench_run.h"

namespace talus::scenes {

/// Exit status of a refused invocation (a bad flag or combination).
inline constexpr int kExitUsage = 2;

struct ScenesOptions {
  std::string scene;
  int parameter = 0;  // 0: the scene's default
  std::string engines;
  int steps = harness::kBenchDefaultSteps;
  std::string format = "csv";
  bool series = false;
  std::vector<int> threads = {1};            // WorldSettings::threads of the Talus backends, one run each
  std::optional<double> perturb;             // metres; absent: unperturbed
  std::optional<int> repeats;                // absent: 1
  std::optional<std::uint64_t> perturbSeed;  // absent: 0
  std::vector<int> iterations = {0};         // Run::iterations per run; 0: the engine's default
  std::vector<int> substeps = {1};           // backend steps of h / N per scene step
};

/// Parses the command line into `options`. The exit status when the
/// program should stop here (0 after --help, kExitUsage for a refused
/// argument, after CLI11 has said why); nothing when it should go on.
std::optional<int> ParseScenesOptions(int argc, char** argv, ScenesOptions& options);

/// Checks what needs no engine: flags that need or exclude each other,
/// the ranges of --perturb and --repeats, counts named twice. Says why on
/// stderr; false when refused.
bool CheckFlagCombinations(const ScenesOptions& options);

/// The engines to run (--engines, or every one `registry` knows), each
/// known and accepting every --iterations and --substeps count; nothing,
/// after saying why on stderr, when refused.
std::optional<std::vector<std::string>> CheckedEngines(const ScenesOptions& options,
                                                       const harness::BackendRegistry& registry);

}  // namespace talus::scenes
