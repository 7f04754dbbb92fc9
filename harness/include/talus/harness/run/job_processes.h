// Isolated jobs: jobs run in worker processes forked from the caller, so
// that an engine that aborts, segfaults, spins forever or allocates
// without bound takes down only its own job. The parent forks at most
// `parallel` workers and hands each, in job order, the next job index
// over a pipe; the worker runs the job and sends back its answer (bytes
// the job's function returns, e.g. a serialised RunResult) on a second
// pipe, its stderr on a third, which the parent passes on to its own
// stderr a line at a time and whose tail it keeps as the engine's last
// message. A shared page holds, per worker, the step its job has reached
// (ReportJobStep), so a crash can be placed at its step. A job that kills
// its worker (a signal, the time limit) ends with that cause, and a fresh
// worker takes the next job; so does a job that threw (the engine's state
// after an exception is not to be trusted).
//
// Why workers that live for many jobs: a fresh process per job cost
// 20 to 45 ms of CPU per job on this machine (its heap's first-touch and
// copy-on-write page faults, expensive under its hypervisor), 5 times the
// default suite's own CPU time; a worker's heap is warm after its first
// job. The results do not depend on which worker ran which job: every
// backend's result is already independent of the jobs run before it in
// the same process (the in-process runner and the shards rely on it too).
//
// Why fork and not a re-executed program: a fork needs no second entry
// point, no re-parsing of scenario files and no serialisation of the runs
// (the workers see the caller's memory, copy on write), and works the
// same from the testbed program and from a test binary. Its rule is that
// only the forking thread exists in the child: the parent here is the
// calling thread alone (the scheduler has no threads), each worker runs
// its jobs on that thread, may start its own threads (a Talus world's),
// and leaves with _exit, so no destructor or atexit handler of the caller
// runs twice and no buffered stdout is written twice. The caller must not
// run other threads while RunInChildProcesses runs (a lock they hold would
// stay locked in the workers); the testbed's callers have none.
//
// Cost: measured in docs/testbed-runner.md ("Isolated jobs").
#pragma once

#include <cstddef>
#include <functional>
#include <string>

namespace talus::harness {

/// What each worker may use; 0 = no limit.
struct ProcessLimits {
  /// Wall-clock seconds from a job's start after which the parent kills
  /// its worker (SIGKILL). A hang inside one engine call ends here.
  double killAfterSeconds = 0.0;
  /// Address space (bytes) a worker may add to what it inherited
  /// (RLIMIT_AS set to its size at start plus this), so it bounds each of
  /// its jobs (memory a job frees is reused by the next). Counted from the
  /// worker's start so that the caller's own size, and a sanitizer's
  /// reserved shadow memory, do not count against the jobs.
  std::size_t memoryBytes = 0;
};

/// How one job ended, as the parent saw it.
struct JobOutcome {
  bool finished = false;  ///< the job returned its answer
  std::string answer;     ///< what the job returned (when finished)
  /// Why not, e.g. "stopped by signal 6 (SIGABRT: Aborted)", "the job
  /// threw std::bad_alloc: ...", "killed by the runner after its
  /// wall-clock budget"; empty when finished.
  std::string failure;
  bool killedForTime = false;  ///< the parent killed it at killAfterSeconds
  /// The last step the job reported (ReportJobStep); kJobNotStepping
  /// before its first, kJobPastSteps after its last.
  int step = -1;
  /// The last lines the job wrote to stderr (at most two, 600
  /// characters), e.g. ODE's assertion before its abort; empty if none.
  std::string lastMessage;
  double wallSeconds = 0.0;  ///< from handing the job out to its answer or its worker's end
};

/// ReportJobStep values besides a step number.
inline constexpr int kJobNotStepping = -1;
inline constexpr int kJobPastSteps = -2;

/// Runs work(i) for every i in [0, count) in worker processes, at most
/// `parallel` (>= 1) at once, handed out in index order. done(i, outcome)
/// is called on the calling thread as each job ends (in the order they
/// end). A std::exception escaping work(i) ends that job with the
/// exception's type and what() as the failure. SIGPIPE is ignored while
/// this runs, and SIGTERM, SIGINT or SIGHUP kill and reap every worker
/// before the program dies of the signal (worker_signals.h; a worker also
/// dies with a SIGKILLed parent). Nothing is left running when this
/// returns or throws.
void RunInChildProcesses(std::size_t count, int parallel, const ProcessLimits& limits,
                         const std::function<std::string(std::size_t)>& work,
                         const std::function<void(std::size_t, JobOutcome)>& done);

/// Inside a worker of RunInChildProcesses: the job has reached `step` (or
/// kJobPastSteps). Does nothing in any other process. One relaxed store to
/// shared memory, cheap enough for every step.
void ReportJobStep(int step);

}  // namespace talus::harness
