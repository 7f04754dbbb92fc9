// The worker pool's terminating-signal handler, its fork-time blocking and
// the worker's side (see worker_signals.h for why each exists).
#include "run/worker_signals.h"

#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstddef>
#include <iterator>

#include "talus/harness/scenario/scenario_limits.h"

namespace talus::harness {
namespace {

constexpr int kTerminating[3] = {SIGTERM, SIGINT, SIGHUP};

// The live workers' pids, 0 in a free slot: a fixed table of lock-free
// atomics, the only kind of shared state a signal handler may read. A pool
// never has more than kMaxJobs workers at once.
static_assert(std::atomic<pid_t>::is_always_lock_free);
std::atomic<pid_t> g_workerPids[kMaxJobs];
// The process whose workers the table holds (a worker, which inherits the
// table and, for an instant, the handler, must not act on it).
std::atomic<pid_t> g_ownerPid{0};

// Kills every recorded worker (SIGKILL: a stopped worker dies too), reaps
// them, and dies of `number` as the default disposition would have made it.
extern "C" void KillWorkersAndDie(int number) {
  if (::getpid() == g_ownerPid.load()) {
    // All first, then the waits: the workers die in parallel.
    for (std::atomic<pid_t>& slot : g_workerPids) {
      const pid_t pid = slot.load();
      if (pid > 0) ::kill(pid, SIGKILL);
    }
    for (std::atomic<pid_t>& slot : g_workerPids) {
      const pid_t pid = slot.exchange(0);
      if (pid <= 0) continue;
      while (::waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
      }
    }
  }
  struct sigaction fallback {};
  fallback.sa_handler = SIG_DFL;
  ::sigemptyset(&fallback.sa_mask);
  ::sigaction(number, &fallback, nullptr);
  sigset_t only;
  ::sigemptyset(&only);
  ::sigaddset(&only, number);
  ::raise(number);                                 // pending: the handler's own mask holds it back ...
  ::pthread_sigmask(SIG_UNBLOCK, &only, nullptr);  // ... until here, where it kills us
  ::_exit(128 + number);                           // not reached
}

}  // namespace

sigset_t TerminatingSignals() {
  sigset_t set;
  ::sigemptyset(&set);
  for (int number : kTerminating) ::sigaddset(&set, number);
  return set;
}

WorkerSignalGuard::WorkerSignalGuard() {
  g_ownerPid.store(::getpid());
  for (std::size_t i = 0; i < std::size(kTerminating); ++i) {
    if (::sigaction(kTerminating[i], nullptr, &m_old[i]) != 0) continue;
    // Ignored by whoever started us (nohup, `cmd &`): it stays ignored.
    if ((m_old[i].sa_flags & SA_SIGINFO) == 0 && m_old[i].sa_handler == SIG_IGN) continue;
    struct sigaction handler {};
    handler.sa_handler = KillWorkersAndDie;
    // One terminating signal at a time: the handler never returns.
    handler.sa_mask = TerminatingSignals();
    m_installed[i] = ::sigaction(kTerminating[i], &handler, nullptr) == 0;
  }
}

WorkerSignalGuard::~WorkerSignalGuard() {
  for (std::size_t i = 0; i < std::size(kTerminating); ++i) {
    if (m_installed[i]) ::sigaction(kTerminating[i], &m_old[i], nullptr);
  }
}

BlockTerminatingSignals::BlockTerminatingSignals() {
  const sigset_t set = TerminatingSignals();
  ::pthread_sigmask(SIG_BLOCK, &set, &m_old);
}

BlockTerminatingSignals::~BlockTerminatingSignals() { ::pthread_sigmask(SIG_SETMASK, &m_old, nullptr); }

bool RecordWorker(pid_t pid) {
  for (std::atomic<pid_t>& slot : g_workerPids) {
    pid_t free = 0;
    if (slot.compare_exchange_strong(free, pid)) return true;
  }
  return false;
}

void ForgetWorker(pid_t pid) {
  for (std::atomic<pid_t>& slot : g_workerPids) {
    pid_t expected = pid;
    if (slot.compare_exchange_strong(expected, 0)) return;
  }
}

void BecomeWorkerProcess(pid_t parent, const sigset_t& mask) {
  struct sigaction fallback {};
  fallback.sa_handler = SIG_DFL;
  ::sigemptyset(&fallback.sa_mask);
  for (int number : kTerminating) {
    struct sigaction inherited {};
    ::sigaction(number, nullptr, &inherited);
    // Only the guard's handler goes; an ignored signal stays ignored.
    if ((inherited.sa_flags & SA_SIGINFO) == 0 && inherited.sa_handler == KillWorkersAndDie) {
      ::sigaction(number, &fallback, nullptr);
    }
  }
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(1);  // the parent died before we asked
  ::pthread_sigmask(SIG_SETMASK, &mask, nullptr);
}

}  // namespace talus::harness
