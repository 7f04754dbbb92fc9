// Each backend declares its thread safety where it registers, and the
// in-process runner (JobIsolation::InProcess) keeps to it: every job of the backends that share one library's
// state runs on one thread, one step at a time, while independent worlds
// run beside them. Nothing is read from a backend's name.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <thread>

#include "support/one_body_run.h"
#include "talus/harness/run/runner.h"
#include "talus/reference/all_backends.h"

namespace talus::harness {
namespace thread_safety_test {

using Runs = std::vector<harness::Run>;  // gtest's Test::Run hides harness::Run

// What the fake backends saw: per backend the threads that stepped it, and
// the most steps of "lib" backends that were ever in flight at once.
struct Record {
  std::mutex mutex;
  std::map<std::string, std::set<std::thread::id>> threads;
  std::atomic<int> sharedInFlight{0};
  std::atomic<int> sharedMostInFlight{0};
};

// One body at rest; each step notes its thread and, for a backend sharing
// "lib", how many such steps overlap, holding the step long enough (50 us)
// for overlaps to happen if the runner allowed them.
class CountingBackend final : public Backend {
 public:
  CountingBackend(std::string name, bool shared, Record& record)
      : m_name(std::move(name)), m_shared(shared), m_record(record) {}
  [[nodiscard]] std::string Name() const override { return m_name; }
  void Step() override {
    {
      std::lock_guard lock(m_record.mutex);
      m_record.threads[m_name].insert(std::this_thread::get_id());
    }
    if (!m_shared) return;
    const int now = ++m_record.sharedInFlight;
    int most = m_record.sharedMostInFlight.load();
    while (now > most && !m_record.sharedMostInFlight.compare_exchange_weak(most, now)) {
    }
    std::this_thread::sleep_for(std::chrono::microseconds(50));
    --m_record.sharedInFlight;
  }
  [[nodiscard]] int BodyCount() const override { return 1; }
  [[nodiscard]] BodyReading GetBodyState(int) const override { return {}; }
  [[nodiscard]] std::vector<ContactReading> GetContacts() const override { return {}; }
  [[nodiscard]] std::vector<Setting> Settings() const override { return {}; }

 private:
  std::string m_name;
  bool m_shared;
  Record& m_record;
};

TEST(ThreadSafety, BackendsSharingALibraryRunOnOneThreadOneStepAtATime) {
  Record record;
  BackendRegistry registry;
  const auto add = [&](const std::string& name, ThreadSafety safety) {
    const bool shared = !safety.sharedStateOf.empty();
    registry.Register(name, "counts its threads", safety,
                      [&record, name, shared](const harness::Run&) -> Result<std::unique_ptr<Backend>> {
                        return std::unique_ptr<Backend>(new CountingBackend(name, shared, record));
                      });
  };
  // Named so that a rule reading the name would get every one of them wrong.
  add("talus-lib-a", ThreadSafety::SharesStateOf("lib"));
  add("other-lib-b", ThreadSafety::SharesStateOf("lib"));
  add("lib-free", ThreadSafety::Independent());
  EXPECT_EQ(registry.GetThreadSafety("other-lib-b").sharedStateOf, "lib");
  EXPECT_TRUE(registry.GetThreadSafety("lib-free").sharedStateOf.empty());

  Runs runs;
  for (int i = 0; i < 8; ++i) runs.push_back(testing_support::OneBodyRun("run" + std::to_string(i), 20));
  RunnerOptions options;
  options.backends = {"talus-lib-a", "other-lib-b", "lib-free"};
  options.jobs = 4;
  options.deterministic = true;
  // The lanes are the in-process runner's (with a process per job no two
  // jobs share a library's state at all).
  options.isolation = JobIsolation::InProcess;
  auto results = RunAll(registry, runs, options);
  ASSERT_TRUE(results) << results.GetError().message;
  ASSERT_EQ(results.Value().size(), 24u);

  std::set<std::thread::id> sharedThreads = record.threads["talus-lib-a"];
  sharedThreads.insert(record.threads["other-lib-b"].begin(), record.threads["other-lib-b"].end());
  EXPECT_EQ(sharedThreads.size(), 1u) << "the two backends sharing \"lib\" ran on more than one thread";
  EXPECT_EQ(record.sharedMostInFlight.load(), 1) << "two steps sharing \"lib\" overlapped";
  EXPECT_EQ(record.threads["lib-free"].count(*sharedThreads.begin()), 0u)
      << "an independent backend ran on the lane of \"lib\"";
}

TEST(ThreadSafety, EveryShippedBackendDeclaresWhatItsLibraryShares) {
  const BackendRegistry& registry = reference::AllBackends();
  for (const std::string& name : registry.Names()) {
    const std::string shared = registry.GetThreadSafety(name).sharedStateOf;
    // Talus worlds own all their state; ODE, Bullet (both builds) and
    // MuJoCo keep process-wide state (docs/testbed-runner.md).
    const std::string expected = name.starts_with("talus")    ? ""
                                 : name.starts_with("ode")    ? "ode"
                                 : name.starts_with("bullet") ? "bullet"
                                 : name.starts_with("mujoco") ? "mujoco"
                                                              : "unexpected backend";
    EXPECT_EQ(shared, expected) << name;
  }
}

}  // namespace thread_safety_test
}  // namespace talus::harness
