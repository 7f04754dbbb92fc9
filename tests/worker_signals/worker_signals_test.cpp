// No orphaned workers (issue 39; harness/src/run/worker_signals.h): the real
// talus-testbed, started in its own session with two long jobs (-j 2), is
// signalled at its own pid alone, as `kill PID` or a job scheduler does,
// never at its process group. Then
//   - SIGTERM or SIGINT: the testbed kills and reaps its workers (one of
//     them SIGSTOPped first, which would otherwise stay stopped for ever)
//     and dies of the signal itself (exit status 128 + signal);
//   - SIGKILL: it can do nothing, and its workers die anyway within a
//     couple of seconds (PR_SET_PDEATHSIG).
// This test process makes itself a child subreaper, so orphaned workers
// are reparented to it rather than to init: what survives is killed and
// reaped here, whatever the outcome, and never left running.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/scratch_files.h"

namespace {

using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

// A process's state letter (R, S, T, Z, ...) and parent; state 0 when it
// is gone.
struct ProcState {
  char state = 0;
  pid_t parent = 0;
};

ProcState ReadState(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t close = text.rfind(')');  // the command name may hold spaces
  if (close == std::string::npos) return {};
  std::istringstream rest(text.substr(close + 1));
  ProcState s;
  rest >> s.state >> s.parent;
  return s;
}

// Alive: exists and is not a zombie (a zombie runs nothing).
bool Alive(pid_t pid) {
  const char state = ReadState(pid).state;
  return state != 0 && state != 'Z' && state != 'X';
}

// Every live process whose parent is `parent`.
std::vector<pid_t> ChildrenOf(pid_t parent) {
  std::vector<pid_t> children;
  for (const fs::directory_entry& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    const pid_t pid = std::stoi(name);
    const ProcState s = ReadState(pid);
    if (s.parent == parent && s.state != 0 && s.state != 'Z') children.push_back(pid);
  }
  return children;
}

// Polls `condition` every 10 ms for up to `seconds`; whether it held.
template <typename Condition>
bool WaitFor(double seconds, Condition condition) {
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < end) {
    if (condition()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return condition();
}

class WorkerSignals : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_EQ(::prctl(PR_SET_CHILD_SUBREAPER, 1), 0); }

  // Whatever is left (the testbed, orphaned workers now ours) is killed
  // and reaped.
  void TearDown() override {
    if (m_testbed > 0 && Alive(m_testbed)) ::kill(m_testbed, SIGKILL);
    for (pid_t worker : m_workers) {
      if (Alive(worker)) ::kill(worker, SIGKILL);
    }
    WaitFor(5.0, [&] {
      while (::waitpid(-1, nullptr, WNOHANG) > 0) {
      }
      return ChildrenOf(::getpid()).empty();
    });
    ::prctl(PR_SET_CHILD_SUBREAPER, 0);
    fs::remove_all(m_out);
  }

  // Starts the testbed in a session of its own on two jobs that each run
  // for minutes (sphere_bounce's 2 s at h = 1e-7: 2e7 steps), and waits
  // until its two workers exist.
  void StartTestbed() {
    m_out = talus::testing_support::FreshScratchDir(
        std::string("worker_signals_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    const std::string scenario = std::string(TALUS_SCENARIO_DIR) + "/bouncing/sphere_bounce.json";
    const std::string out = m_out.string();
    m_testbed = ::fork();
    ASSERT_GE(m_testbed, 0);
    if (m_testbed == 0) {
      ::setsid();  // its own session and process group: a signal to it reaches it alone
      // Whatever this test inherited, the testbed starts with the defaults.
      for (int number : {SIGTERM, SIGINT, SIGHUP}) ::signal(number, SIG_DFL);
      sigset_t none;
      ::sigemptyset(&none);
      ::sigprocmask(SIG_SETMASK, &none, nullptr);
      ::execl(TALUS_TESTBED_BINARY, TALUS_TESTBED_BINARY, "run", scenario.c_str(), "-b", "talus,talus-split",
              "--time-step", "1e-7", "-j", "2", "-q", "-o", out.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ASSERT_TRUE(WaitFor(60.0,
                        [&] {
                          m_workers = ChildrenOf(m_testbed);
                          return m_workers.size() >= 2;
                        }))
        << "the testbed started " << ChildrenOf(m_testbed).size() << " workers";
  }

  // The testbed's end within `seconds`: its wait status, -1 if it lives on.
  int WaitForTestbed(double seconds) {
    int status = -1;
    WaitFor(seconds, [&] {
      int got = 0;
      if (::waitpid(m_testbed, &got, WNOHANG) != m_testbed) return false;
      status = got;
      m_testbed = -1;
      return true;
    });
    return status;
  }

  bool WorkersGone(double seconds) {
    return WaitFor(seconds, [&] {
      for (pid_t worker : m_workers) {
        if (Alive(worker)) return false;
      }
      return true;
    });
  }

  std::string LiveWorkers() const {
    std::string list;
    for (pid_t worker : m_workers) {
      if (Alive(worker)) list += std::to_string(worker) + " (" + ReadState(worker).state + ") ";
    }
    return list;
  }

  pid_t m_testbed = -1;
  std::vector<pid_t> m_workers;
  fs::path m_out;
};

// SIGTERM and SIGINT at the parent alone: the workers are killed and
// reaped, a stopped one included, and the parent dies of the signal.
TEST_F(WorkerSignals, TerminatingSignalToTheParentAloneKillsItsWorkers) {
  for (int number : {SIGTERM, SIGINT}) {
    SCOPED_TRACE(::strsignal(number));
    StartTestbed();
    ASSERT_GE(m_workers.size(), 2u);
    ASSERT_EQ(::kill(m_workers[0], SIGSTOP), 0);
    ASSERT_TRUE(WaitFor(5.0, [&] { return ReadState(m_workers[0]).state == 'T'; }));
    ASSERT_EQ(::kill(m_testbed, number), 0);
    const int status = WaitForTestbed(5.0);
    ASSERT_NE(status, -1) << "the testbed did not end within 5 s of " << ::strsignal(number);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == number)
        << "wait status " << status << ": not killed by the signal itself (shell status 128 + " << number
        << ")";
    EXPECT_TRUE(WorkersGone(3.0)) << "workers alive after " << ::strsignal(number)
                                  << " to the parent: " << LiveWorkers();
    TearDown();
    SetUp();
  }
}

// SIGKILL at the parent: nothing runs in it, and the workers die anyway.
TEST_F(WorkerSignals, WorkersDieWithAKilledParent) {
  StartTestbed();
  ASSERT_EQ(::kill(m_testbed, SIGKILL), 0);
  const int status = WaitForTestbed(5.0);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << status;
  EXPECT_TRUE(WorkersGone(2.0)) << "workers alive 2 s after SIGKILL to the parent: " << LiveWorkers();
}

}  // namespace
