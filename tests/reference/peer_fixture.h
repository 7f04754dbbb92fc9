// What the reference tests share: one registry of the peer backends (Bullet,
// ODE, MuJoCo, each in every configuration this build has), scenario files
// loaded from scenarios/, and a backend built for a run, with a test failure
// naming the backend when it is refused.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "talus/harness/backend/backend.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/reference/bullet_backend.h"
#include "talus/reference/mujoco_backend.h"
#include "talus/reference/ode_backend.h"

namespace talus::reference::test {

inline const harness::BackendRegistry& PeerRegistry() {
  static const harness::BackendRegistry registry = [] {
    harness::BackendRegistry r;
    RegisterBulletBackends(r);
    RegisterOdeBackends(r);
    RegisterMujocoBackends(r);
    return r;
  }();
  return registry;
}

/// Every run of scenarios/<file> (sweeps expanded); none after a test failure.
inline std::vector<harness::Run> LoadRuns(const std::string& file) {
  auto runs = harness::LoadScenarioFile(std::string(TALUS_SCENARIO_DIR) + "/" + file);
  EXPECT_TRUE(runs) << runs.GetError().message;
  return runs ? runs.Value() : std::vector<harness::Run>{};
}

/// The first run of scenarios/<file>; an empty run after a test failure.
inline harness::Run LoadRun(const std::string& file) {
  std::vector<harness::Run> runs = LoadRuns(file);
  return runs.empty() ? harness::Run{} : runs[0];
}

/// The named peer built for `run`; null after a test failure naming it.
inline std::unique_ptr<harness::Backend> Build(const std::string& name, const harness::Run& run) {
  auto backend = PeerRegistry().Create(name, run);
  EXPECT_TRUE(backend) << name << ": " << backend.GetError().message;
  return backend ? std::move(backend).Value() : nullptr;
}

/// The double-precision Bullet and both ODE steppers, each in its defaults
/// and tuned configuration: the peers every build has.
inline std::vector<std::string> BulletAndOdePeers() {
  return {"bullet", "bullet-tuned", "ode-step", "ode-step-tuned", "ode-quickstep", "ode-quickstep-tuned"};
}

/// A peer's name as a test name: gtest allows no '-' ("ode-step" -> "ode_step").
inline std::string PeerTestName(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

}  // namespace talus::reference::test
