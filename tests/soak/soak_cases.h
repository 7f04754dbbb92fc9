// The soak suite's runs and its verdict on each result (issue 14, "Long runs
// and physics abuse"), shared by the full suite (soak_test.cpp, ctest label
// soak, `make soak`) and its shortened form in CI (soak_short_test.cpp,
// label slow: Release only).
//
// The verdict does not judge accuracy, only survival: every job finishes,
// and a job that ends early says why with the step, the engine and, for a
// non-finite state, the body ("step 812: bullet: body \"spinner\":
// non-finite position (nan, nan, nan)", the runner's per-step check).
// Talus itself must stay finite or stop with its own refusal.
#pragma once

#include <algorithm>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "talus/harness/run/runner.h"
#include "talus/harness/scenario/scenario_loader.h"

namespace talus::harness::soak {

/// The first run of every scenario file under scenarios/ (every family),
/// each set to `steps` steps at its own time step.
inline std::vector<Run> FamilyRuns(int steps) {
  std::vector<Run> runs;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(TALUS_SCENARIO_DIR)) {
    if (entry.path().extension() == ".json" && entry.path().filename() != "schema.json") {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    auto loaded = LoadScenarioFile(file);
    if (!loaded || loaded.Value().empty()) continue;  // the loader's own tests cover bad files
    Run run = loaded.Value().front();
    run.steps = steps;
    run.scenario.world.steps = steps;
    // Survival, not accuracy: a converged-reference truth would add a run
    // 16 times longer, and the others judge a duration they were not
    // written for.
    run.scenario.truths.clear();
    runs.push_back(std::move(run));
  }
  return runs;
}

/// `count` dynamic unit boxes all at the same position above a ground box:
/// every pair overlaps completely (the probe's 1000 coincident boxes).
inline Run CoincidentBoxes(int count, int steps) {
  Run run;
  run.id = "coincident_boxes_" + std::to_string(count);
  run.scenario.name = run.id;
  BodySpec ground{.name = "ground", .shape = BoxShape{Vec3(20, 0.5, 20)}, .motion = Motion::Static};
  ground.position = Vec3(0, -0.5, 0);
  run.scenario.bodies.push_back(ground);
  for (int i = 0; i < count; ++i) {
    BodySpec box{.name = "box" + std::to_string(i), .shape = BoxShape{Vec3(0.5, 0.5, 0.5)}};
    box.position = Vec3(0, 0.5, 0);
    box.density = 1000.0;
    run.scenario.bodies.push_back(box);
  }
  run.scenario.measure = {Quantity::Position};
  run.timeStep = run.scenario.world.timeStep;
  run.steps = steps;
  run.scenario.world.steps = steps;
  return run;
}

/// The abuse cases: tests/data/soak/*.json (spin 1e6 rad/s, speed 1e6 m/s,
/// a 1e9 mass ratio in a stack, gravity 1e6 m/s^2) at `steps` steps each,
/// then `boxes` coincident boxes at `boxSteps` steps.
inline std::vector<Run> AbuseRuns(int steps, int boxes, int boxSteps) {
  std::vector<Run> runs;
  for (const char* name : {"spin_1e6", "speed_1e6", "mass_ratio_1e9_stack", "gravity_1e6"}) {
    auto loaded = LoadScenarioFile(std::string(TALUS_TEST_DATA_DIR) + "/soak/" + name + ".json");
    if (!loaded) throw std::runtime_error(loaded.GetError().message);
    Run run = loaded.Value().front();
    run.steps = steps;
    run.scenario.world.steps = steps;
    runs.push_back(std::move(run));
  }
  runs.push_back(CoincidentBoxes(boxes, boxSteps));
  return runs;
}

/// The parts of a step failure message "step N: <backend>: <reason>".
struct StepFailureText {
  std::string backend;
  std::string reason;
};

/// `error` split as a step failure, or nothing when it is not one (N must be
/// digits, the backend non-empty and free of ':', the reason non-empty).
inline std::optional<StepFailureText> ParseStepFailure(const std::string& error) {
  constexpr std::string_view kPrefix = "step ";
  if (error.rfind(kPrefix, 0) != 0) return std::nullopt;
  std::size_t at = kPrefix.size();
  const std::size_t digits = at;
  while (at < error.size() && error[at] >= '0' && error[at] <= '9') ++at;
  if (at == digits || error.compare(at, 2, ": ") != 0) return std::nullopt;
  const std::size_t backendStart = at + 2;
  const std::size_t backendEnd = error.find(':', backendStart);
  if (backendEnd == std::string::npos || backendEnd == backendStart ||
      error.compare(backendEnd, 2, ": ") != 0)
    return std::nullopt;
  std::string reason = error.substr(backendEnd + 2);
  if (reason.empty()) return std::nullopt;
  return StepFailureText{error.substr(backendStart, backendEnd - backendStart), std::move(reason)};
}

/// "" when `result` passes the soak verdict, else why not.
inline std::string SoakVerdict(const RunResult& result) {
  const std::string job = result.runId + " on " + result.backend + ": ";
  if (result.error.empty()) {
    if (result.steps <= 0) return job + "no error but no steps taken";
    return {};
  }
  const bool talus = result.backend.rfind("talus", 0) == 0;
  // A failed step: "step N: <backend>: <reason>". (Parsed by hand: GCC 12
  // mis-warns -Wmaybe-uninitialized inside std::regex under the sanitizers.)
  if (const std::optional<StepFailureText> failure = ParseStepFailure(result.error)) {
    if (failure->backend != result.backend) return job + "the failure names another engine: " + result.error;
    const std::string& reason = failure->reason;
    if (reason.find("non-finite") != std::string::npos) {
      if (reason.rfind("body \"", 0) != 0)
        return job + "a non-finite state without its body: " + result.error;
      if (talus) return job + "Talus produced a non-finite state: " + result.error;
    }
    return {};
  }
  // Refused before stepping (the engine cannot take the input safely): the
  // message names the body, or starts with the engine ("mujoco: the world
  // needs at least 2502 MB of mjData ..." for mujoco and mujoco-tuned).
  if (result.error.find("body \"") != std::string::npos) return {};
  const std::size_t colon = result.error.find(": ");
  if (colon != std::string::npos && colon > 0 &&
      result.backend.rfind(result.error.substr(0, colon), 0) == 0) {
    return {};
  }
  return job + "an error that names no step, engine or body: " + result.error;
}

}  // namespace talus::harness::soak
