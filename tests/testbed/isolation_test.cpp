// Every job in its own process (JobIsolation::Process): an engine that
// aborts, segfaults, hangs past the budget, runs out of its memory limit
// or diverges to NaN stops its own cell, named with its cause and step,
// and every other cell of results.json is the same bytes as in a run
// without it, at any --jobs; the in-process path gives the same bytes.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "support/one_body_run.h"
#include "talus/harness/run/results_file.h"
#include "talus/harness/run/runner.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/reference/all_backends.h"

// In the sanitizer tree, ASan would catch the fake engine's segfault
// itself and exit with its own status and a report naming the process id,
// so the cell's text would differ from run to run; left to the kernel, it
// stays the SIGSEGV the runner names. Other crashes in this binary still
// stop their test under ASan, only without its report.
#if defined(__SANITIZE_ADDRESS__)
extern "C" const char* __asan_default_options() { return "handle_segv=0"; }
#endif

namespace talus::harness {
namespace isolation_test {

using testing_support::OneBodyRun;
using Runs = std::vector<harness::Run>;  // gtest's Test::Run hides harness::Run

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

enum class Misdeed { None, Abort, Segfault, Hang, NaN, Allocate, AllocateUnchecked, Slow };

// One body falling at 1 m/s that misbehaves at step `at` as asked.
class MisbehavingBackend final : public Backend {
 public:
  MisbehavingBackend(std::string name, Misdeed misdeed, int at)
      : m_name(std::move(name)), m_misdeed(misdeed), m_at(at) {}
  [[nodiscard]] std::string Name() const override { return m_name; }
  void Step() override {
    ++m_step;
    m_state.origin.y() -= 0.01;
    m_state.centerOfMass = m_state.origin;
    // 5 ms every step: a large scene's cost, 10 times the hard kill's
    // grace over 1024 steps.
    if (m_misdeed == Misdeed::Slow) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (m_step != m_at) return;
    switch (m_misdeed) {
      case Misdeed::None:
      case Misdeed::Slow:
        break;
      case Misdeed::Abort:
        std::fprintf(stderr, "fake engine: internal assertion \"x > 0\" failed\n");
        std::abort();
      case Misdeed::Segfault: {
        volatile int* nowhere = nullptr;
        *nowhere = 1;
        break;
      }
      case Misdeed::Hang: {
        volatile unsigned long spins = 0;
        while (true) spins = spins + 1;
      }
      case Misdeed::NaN:
        m_state.origin.setConstant(std::numeric_limits<double>::quiet_NaN());
        break;
      case Misdeed::Allocate:
        // 64 MiB at a time, each written so it is really used, kept.
        while (true) {
          m_hoard.emplace_back(std::size_t{64} << 20, 1);
        }
      case Misdeed::AllocateUnchecked:
        // Bullet's way: malloc until it fails, then use the null it gave
        // (SIGSEGV), never throwing std::bad_alloc.
        while (true) {
          constexpr std::size_t kChunk = std::size_t{64} << 20;
          auto* chunk = static_cast<volatile char*>(std::malloc(kChunk));
          for (std::size_t i = 0; i < kChunk; i += 4096) chunk[i] = 1;
          m_unchecked.push_back(const_cast<char*>(chunk));
        }
    }
  }
  [[nodiscard]] int BodyCount() const override { return 1; }
  [[nodiscard]] BodyReading GetBodyState(int) const override { return m_state; }
  [[nodiscard]] std::vector<ContactReading> GetContacts() const override { return {}; }
  [[nodiscard]] std::vector<Setting> Settings() const override { return {{"misdeed", m_name}}; }

 private:
  std::string m_name;
  Misdeed m_misdeed;
  int m_at;
  int m_step = 0;
  BodyReading m_state;
  std::vector<std::vector<char>> m_hoard;
  std::vector<char*> m_unchecked;  // never freed: the process dies holding them
};

BackendRegistry MisbehavingRegistry() {
  BackendRegistry registry;
  const auto add = [&](const std::string& name, Misdeed misdeed, int at) {
    registry.Register(name, "test backend: " + name, ThreadSafety::Independent(),
                      [=](const harness::Run&) -> Result<std::unique_ptr<Backend>> {
                        return std::unique_ptr<Backend>(new MisbehavingBackend(name, misdeed, at));
                      });
  };
  add("fine", Misdeed::None, 0);
  add("also-fine", Misdeed::None, 0);
  add("aborts", Misdeed::Abort, 3);
  add("segfaults", Misdeed::Segfault, 2);
  add("hangs", Misdeed::Hang, 4);
  add("diverges", Misdeed::NaN, 5);
  add("allocates", Misdeed::Allocate, 6);
  add("allocates-unchecked", Misdeed::AllocateUnchecked, 6);
  add("slow", Misdeed::Slow, 0);
  return registry;
}

RunnerOptions Options(std::vector<std::string> backends, int jobs) {
  RunnerOptions options;
  options.backends = std::move(backends);
  options.deterministic = true;
  options.jobs = jobs;
  return options;
}

const Runs kRuns{OneBodyRun("first", 20), OneBodyRun("second", 20)};

// The results file's entry of each result, for cell-by-cell comparison.
std::vector<std::string> Cells(const std::vector<RunResult>& results) {
  std::vector<std::string> cells;
  for (const RunResult& result : results) cells.push_back(ResultsToJson(ResultsFile{{}, true, {result}}));
  return cells;
}

TEST(Isolation, CrashingAndDivergingEnginesStopOnlyTheirOwnCellsNamingTheCause) {
  auto healthy = RunAll(MisbehavingRegistry(), kRuns, Options({"fine", "also-fine"}, 1));
  ASSERT_TRUE(healthy) << healthy.GetError().message;
  const std::vector<std::string> healthyCells = Cells(healthy.Value());
  ASSERT_EQ(healthyCells.size(), 4u);
  std::string firstFile;
  for (const int jobs : {1, 2, 5}) {
    auto results = RunAll(MisbehavingRegistry(), kRuns,
                          Options({"fine", "aborts", "segfaults", "diverges", "also-fine"}, jobs));
    ASSERT_TRUE(results) << results.GetError().message;
    const std::vector<RunResult>& r = results.Value();
    ASSERT_EQ(r.size(), 10u);
    const std::vector<std::string> cells = Cells(r);
    for (std::size_t run = 0; run < 2; ++run) {
      const std::size_t at = run * 5;
      // The healthy cells: the same bytes as in the run without the others.
      EXPECT_EQ(cells[at], healthyCells[run * 2]) << jobs << " jobs";
      EXPECT_EQ(cells[at + 4], healthyCells[run * 2 + 1]) << jobs << " jobs";
      // The cause, its step and the engine's last message.
      EXPECT_EQ(r[at + 1].error.rfind("step 3: aborts: stopped by signal 6 (SIGABRT", 0), 0u)
          << r[at + 1].error;
      EXPECT_TRUE(Has(r[at + 1].error, "last message: fake engine: internal assertion \"x > 0\" failed"))
          << r[at + 1].error;
      // A sanitizer build reports the segfault itself before exiting; both
      // name it, and the step.
      EXPECT_EQ(r[at + 2].error.rfind("step 2: segfaults: ", 0), 0u) << r[at + 2].error;
      EXPECT_TRUE(Has(r[at + 2].error, "SEGV")) << r[at + 2].error;
      EXPECT_EQ(r[at + 3].error, "step 5: diverges: body \"b\": non-finite position (nan, nan, nan)");
      // Stopped cells keep their identity, for the report's rows.
      for (std::size_t b = 1; b <= 3; ++b) {
        EXPECT_EQ(r[at + b].runId, kRuns[run].id);
        EXPECT_EQ(r[at + b].steps, 20);
        EXPECT_TRUE(r[at + b].metrics.empty());
      }
    }
    const std::string file =
        ResultsToJson(ResultsFile{{"fine", "aborts", "segfaults", "diverges", "also-fine"}, true, r});
    if (firstFile.empty()) {
      firstFile = file;
    } else {
      EXPECT_EQ(file, firstFile) << jobs << " jobs";
    }
  }
}

TEST(Isolation, AHangIsKilledAtTheBudgetAndTheOthersFinish) {
  RunnerOptions options = Options({"fine", "hangs"}, 2);
  // The hang is inside one step, where the job's own budget check (after
  // every step) never comes: the runner kills it kBudgetKillGraceSeconds
  // after the budget.
  options.budgetSeconds = 0.5;
  auto results = RunAll(MisbehavingRegistry(), {OneBodyRun("first", 20)}, options);
  ASSERT_TRUE(results) << results.GetError().message;
  const std::vector<RunResult>& r = results.Value();
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].error, "");
  EXPECT_EQ(r[0].series.time.size(), 21u);
  EXPECT_EQ(r[1].error,
            "step 4: hangs: wall-clock budget spent: the runner killed the job's process after 2.5 s");
}

TEST(Isolation, SlowStepsStopSoftlyAtTheBudgetKeepingTheirPlot) {
  // 5 ms a step: the budget is checked after every step (issue 39), so the
  // job stops itself at the first step past 0.5 s, with its partial plot,
  // instead of running on to a check 1024 steps later (5 s) and being
  // killed by the runner at 2.5 s with nothing kept.
  RunnerOptions options = Options({"fine", "slow"}, 2);
  options.budgetSeconds = 0.5;
  auto results = RunAll(MisbehavingRegistry(), {OneBodyRun("first", 100000)}, options);
  ASSERT_TRUE(results) << results.GetError().message;
  const std::vector<RunResult>& r = results.Value();
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].error, "");
  const std::string& stopped = r[1].error;
  EXPECT_EQ(stopped.rfind("step ", 0), 0u) << stopped;
  EXPECT_TRUE(Has(stopped, ": slow: wall-clock budget of 0.5 s spent")) << stopped;
  EXPECT_FALSE(Has(stopped, "killed")) << stopped;
  // Stopped at at most 100 steps (0.5 s / 5 ms), the plot up to there kept,
  // ending at the step it stopped at (the samples, every 500th step of
  // 100000, would otherwise hold step 0 alone).
  const int step = std::stoi(stopped.substr(5));
  EXPECT_GE(step, 10);   // a loaded machine sleeps longer than asked: fewer steps
  EXPECT_LE(step, 101);  // never more: each step sleeps at least 5 ms
  ASSERT_GE(r[1].series.time.size(), 2u);
  EXPECT_NEAR(r[1].series.time.back(), step * 0.01, 1e-9);
}

TEST(Isolation, AJobPastItsMemoryLimitStopsNamingTheLimit) {
  RunnerOptions options = Options({"fine", "allocates"}, 2);
  options.memoryLimitBytes = std::size_t{256} << 20;
  auto results = RunAll(MisbehavingRegistry(), {OneBodyRun("first", 20)}, options);
  ASSERT_TRUE(results) << results.GetError().message;
  const std::vector<RunResult>& r = results.Value();
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].error, "");
  EXPECT_EQ(r[1].error.rfind("step 6: allocates: ", 0), 0u) << r[1].error;
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer's allocator reports the failed allocation and exits
  // before operator new can throw.
  EXPECT_TRUE(Has(r[1].error, "AddressSanitizer")) << r[1].error;
#else
  EXPECT_TRUE(Has(r[1].error, "ran out of memory (std::bad_alloc) within the job's limit of 256 MiB"))
      << r[1].error;
#endif
}

// An engine that crashes on a failed allocation (Bullet) instead of
// throwing: the signal is named, and beside it the limit it likely ran
// out of, with the process's peak resident memory.
TEST(Isolation, ACrashUnderAMemoryLimitNamesTheLimit) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's allocator reports the failed malloc itself";
#endif
  RunnerOptions options = Options({"fine", "allocates-unchecked"}, 2);
  options.memoryLimitBytes = std::size_t{256} << 20;
  auto results = RunAll(MisbehavingRegistry(), {OneBodyRun("first", 20)}, options);
  ASSERT_TRUE(results) << results.GetError().message;
  const std::vector<RunResult>& r = results.Value();
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].error, "");
  EXPECT_EQ(r[1].error.rfind("step 6: allocates-unchecked: stopped by signal 11 (SIGSEGV: ", 0), 0u)
      << r[1].error;
  EXPECT_TRUE(Has(r[1].error,
                  "; the job ran under a memory limit of 256 MiB (--memory-limit) and likely ran out of "
                  "memory (its process's peak resident memory: "))
      << r[1].error;
  // Without a limit a segfault says nothing of memory.
  auto unlimited = RunAll(MisbehavingRegistry(), {OneBodyRun("first", 20)}, Options({"segfaults"}, 1));
  ASSERT_TRUE(unlimited) << unlimited.GetError().message;
  EXPECT_FALSE(Has(unlimited.Value()[0].error, "memory")) << unlimited.Value()[0].error;
}

TEST(Isolation, BadLimitsAreRefusedBeforeAnythingRuns) {
  RunnerOptions options = Options({"fine"}, 1);
  options.budgetSeconds = std::numeric_limits<double>::quiet_NaN();
  auto refused = RunAll(MisbehavingRegistry(), kRuns, options);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.GetError().message, "budget n/a s is not in [0, 1e+06] (0 = none)");
  options.budgetSeconds = 0.0;
  options.memoryLimitBytes = 1 << 20;
  refused = RunAll(MisbehavingRegistry(), kRuns, options);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.GetError().message,
            "memory limit 1048576 bytes is not 0 (none) or in [16777216, 1099511627776]");
  options.memoryLimitBytes = std::size_t{64} << 20;
  options.isolation = JobIsolation::InProcess;
  refused = RunAll(MisbehavingRegistry(), kRuns, options);
  ASSERT_FALSE(refused);
  EXPECT_TRUE(Has(refused.GetError().message, "needs each job in its own process"));
}

TEST(Isolation, ProcessAndInProcessJobsWriteTheSameResultsFile) {
  // Every engine on two shipped scenarios: a result that crossed the
  // process boundary must be the same bytes as one that did not.
  auto runs = LoadScenarios({std::string(TALUS_SCENARIO_DIR) + "/stacking/hull_rest.json",
                             std::string(TALUS_SCENARIO_DIR) + "/sliding/box_slide.json"});
  ASSERT_TRUE(runs) << runs.GetError().message;
  const std::vector<std::string> backends = reference::AllBackends().Names();
  std::string inProcess;
  for (const JobIsolation isolation : {JobIsolation::InProcess, JobIsolation::Process}) {
    RunnerOptions options = Options(backends, 2);
    options.isolation = isolation;
    auto results = RunAll(reference::AllBackends(), runs.Value(), options);
    ASSERT_TRUE(results) << results.GetError().message;
    const std::string file = ResultsToJson(ResultsFile{backends, true, results.Value()});
    if (inProcess.empty()) {
      inProcess = file;
    } else {
      EXPECT_EQ(file, inProcess);
    }
  }
}

// Every backend's cells on `runs`, and the cells of the backends that
// finished, run again alone: the same bytes.
void ExpectNoEngineCostsAnotherItsResults(const Runs& runs) {
  const std::vector<std::string> backends = reference::AllBackends().Names();
  auto all = RunAll(reference::AllBackends(), runs, Options(backends, 2));
  ASSERT_TRUE(all) << all.GetError().message;
  ASSERT_EQ(all.Value().size(), backends.size() * runs.size());
  std::vector<std::string> finished;
  std::vector<RunResult> finishedResults;
  for (const RunResult& result : all.Value()) {
    // Whatever an engine did, its cell says why in words, never a bare crash.
    EXPECT_FALSE(Has(result.error, "stopped by signal")) << result.backend << ": " << result.error;
    if (!result.error.empty()) continue;
    finished.push_back(result.backend);
    finishedResults.push_back(result);
  }
  ASSERT_FALSE(finished.empty());
  auto alone = RunAll(reference::AllBackends(), runs, Options(finished, 1));
  ASSERT_TRUE(alone) << alone.GetError().message;
  EXPECT_EQ(Cells(alone.Value()), Cells(finishedResults));
}

TEST(Isolation, TheSeventeenBlockArchCostsNoEngineItsResults) {
  // ODE aborted on this arch and took every result with it (issue 26).
  auto runs = LoadScenarios({std::string(TALUS_TEST_DATA_DIR) + "/isolation/arch_17.json"});
  ASSERT_TRUE(runs) << runs.GetError().message;
  ExpectNoEngineCostsAnotherItsResults(runs.Value());
}

TEST(Isolation, OdeStopsAtAZeroNormalContactInsteadOfAborting) {
  // In this process: before the backend's check, ODE aborted the runner.
  auto runs = LoadScenarios({std::string(TALUS_TEST_DATA_DIR) + "/isolation/ode_wedge_on_ground.json"});
  ASSERT_TRUE(runs) << runs.GetError().message;
  RunnerOptions options = Options({"ode-step", "ode-quickstep"}, 1);
  options.isolation = JobIsolation::InProcess;
  auto results = RunAll(reference::AllBackends(), runs.Value(), options);
  ASSERT_TRUE(results) << results.GetError().message;
  for (const RunResult& r : results.Value()) {
    EXPECT_EQ(r.error.rfind("step 1: " + r.backend +
                                ": ODE's collider returned a contact between \"block00\" and \"ground\" with "
                                "normal (-0, -0, -0)",
                            0),
              0u)
        << r.error;
  }
}

TEST(Isolation, AHullOfPointsWithinAPicometreCostsNoEngineItsResults) {
  // The loader refuses this hull (scenario_degenerate_body_test.cpp); a run
  // made in code still reaches the engines, and ODE aborted in dMassCheck.
  harness::Run run = OneBodyRun("tiny_hull", 30);
  run.scenario.bodies[0].name = "box";
  run.scenario.bodies[0].shape = BoxShape{Vec3(0.5, 0.5, 0.5)};
  BodySpec tiny{.name = "tiny",
                .shape = HullShape{{Vec3(1.0, 0.0, 0.0), Vec3(1.0 + 1e-12, 0.0, 0.0), Vec3(1.0, 1e-12, 0.0),
                                    Vec3(1.0, 0.0, 1e-12), Vec3(1.0 + 1e-12, 1e-12, 1e-12)}}};
  tiny.position = Vec3(2.0, 0.0, 0.0);
  tiny.density = 1000.0;
  run.scenario.bodies.push_back(tiny);
  ExpectNoEngineCostsAnotherItsResults({run});
}

}  // namespace isolation_test
}  // namespace talus::harness
