// OneBodyRun: the smallest run the runner accepts (one 0.5 m sphere of
// water density, h = 0.01 s), for the tests that drive the runner with a
// fake backend and need no scenario file.
#pragma once

#include <string>

#include "talus/harness/scenario/scenario.h"

namespace talus::testing_support {

/// A run named `id` (run id and scenario name) of `steps` steps.
inline harness::Run OneBodyRun(const std::string& id, int steps) {
  harness::Run run;
  run.id = id;
  run.scenario.name = id;
  run.scenario.bodies.push_back(harness::BodySpec{.name = "b", .shape = harness::SphereShape{0.5}});
  run.scenario.bodies[0].density = 1000.0;
  run.timeStep = 0.01;
  run.steps = steps;
  return run;
}

}  // namespace talus::testing_support
