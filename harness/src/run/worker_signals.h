// No orphaned workers (issue 39): what the worker pool of
// RunInChildProcesses (job_processes.cpp) does with the signals that end a
// program, so that its forked workers never outlive it.
//
// The problem: a job scheduler, `kill PID` or a supervisor sends SIGTERM
// (or SIGINT) to the testbed's pid alone, not to its process group. With
// the default disposition the parent dies at once and its workers, which
// never see the signal, run on as orphans: with -q for up to the 1800 s
// default budget, and a SIGSTOPped worker stays stopped for ever. Two
// mechanisms close it, one per way the parent can die:
//
// - A signal it can catch (SIGTERM, SIGINT, SIGHUP): WorkerSignalGuard
//   installs a handler for the pool's lifetime that SIGKILLs every worker
//   recorded here (RecordWorker), reaps them, then restores the default
//   disposition and re-raises the signal, so the program still dies of it
//   and its exit status is the conventional 128 + signal. The handler
//   does only async-signal-safe work (kill, waitpid, sigaction,
//   pthread_sigmask, raise on a fixed table of lock-free atomics) and does
//   it itself rather than setting a flag for the poll loop: the parent may
//   be anywhere when the signal comes (inside a job's `done` callback,
//   writing a file), and the point is that it dies promptly.
// - A signal it cannot catch (SIGKILL, the OOM killer) or a crash: each
//   worker asks the kernel for SIGKILL when its parent dies
//   (prctl(PR_SET_PDEATHSIG), BecomeWorkerProcess).
//
// Races, and why the fork is wrapped in BlockTerminatingSignals: with the
// signals blocked from before the fork until the new pid is recorded, the
// handler can never run while a worker exists that it does not know of.
// In the child, the handler's disposition is reset before the signals are
// unblocked, and PDEATHSIG is set before getppid() is compared with the
// pid recorded before the fork: a parent that died in between (its
// death signal would have been sent before we asked for it) leaves the
// child reparented, which the comparison catches and ends at once.
//
// A signal the caller's environment ignores (a shell's `cmd &` without job
// control ignores SIGINT, nohup SIGHUP) stays ignored: the guard takes over
// only signals that would have killed the program.
//
// PR_SET_PDEATHSIG fires when the *thread* that forked ends; the pool
// forks from the calling thread, which stays inside RunInChildProcesses
// for the workers' whole life, so that is the parent's death here.
#pragma once

#include <signal.h>
#include <sys/types.h>

namespace talus::harness {

/// The signals the guard handles: SIGTERM, SIGINT, SIGHUP.
sigset_t TerminatingSignals();

/// While alive, each terminating signal the program does not ignore runs
/// the handler described above; the previous dispositions come back when
/// it is destroyed. One at a time per process (the pool's callers have no
/// threads).
class WorkerSignalGuard {
 public:
  WorkerSignalGuard();
  ~WorkerSignalGuard();
  WorkerSignalGuard(const WorkerSignalGuard&) = delete;
  WorkerSignalGuard& operator=(const WorkerSignalGuard&) = delete;

 private:
  struct sigaction m_old[3]{};
  bool m_installed[3] = {};
};

/// Blocks the terminating signals on this thread until destroyed (the old
/// mask then comes back); `Old()` is the mask to restore in a child.
class BlockTerminatingSignals {
 public:
  BlockTerminatingSignals();
  ~BlockTerminatingSignals();
  BlockTerminatingSignals(const BlockTerminatingSignals&) = delete;
  BlockTerminatingSignals& operator=(const BlockTerminatingSignals&) = delete;
  const sigset_t& Old() const { return m_old; }

 private:
  sigset_t m_old{};
};

/// In the parent, with the signals blocked: `pid` is a worker the handler
/// must kill. False when the table is full (more workers than
/// kMaxJobs at once cannot happen; PDEATHSIG would still cover it).
bool RecordWorker(pid_t pid);

/// In the parent, before waitpid reaps `pid`: the handler must no longer
/// touch it (once reaped, its pid may be another process's).
void ForgetWorker(pid_t pid);

/// In a new worker, first thing after fork (signals still blocked): the
/// default dispositions back, SIGKILL on the parent's death, an immediate
/// _exit if `parent` (getpid() before the fork) is already gone, then the
/// signal mask `mask` (the parent's before it blocked them).
void BecomeWorkerProcess(pid_t parent, const sigset_t& mask);

}  // namespace talus::harness
