// Jobs in worker processes (see job_processes.h): fork, limits, the poll
// loop that hands out jobs and gathers answers and stderr, the kill at the
// time limit, and the description of how a job's worker died.
#include "talus/harness/run/job_processes.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <exception>
#include <new>
#include <stdexcept>
#include <typeinfo>
#include <vector>

#include "run/worker_signals.h"
#include "support/text_util.h"

namespace talus::harness {
namespace {

using Clock = std::chrono::steady_clock;

// In a child: its slot of the shared step page; null everywhere else.
std::atomic<int>* g_stepSlot = nullptr;

// Bytes of a child's stderr kept for its last message.
constexpr std::size_t kStderrTail = 4096;
// Characters of the last message kept in an outcome.
constexpr std::size_t kLastMessageChars = 600;

// The answer pipe's first byte says what follows.
constexpr char kAnswerTag = 'R';
constexpr char kFailureTag = 'E';

void WriteAll(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t written = ::write(fd, data, size);
    if (written < 0) {
      if (errno == EINTR) continue;
      return;  // the parent is gone or the pipe broke: nothing left to tell
    }
    data += written;
    size -= static_cast<std::size_t>(written);
  }
}

// The process's address space in bytes (/proc/self/statm, first field in
// pages), read with plain syscalls: 0 when it cannot be read.
std::size_t AddressSpaceBytes() {
  const int fd = ::open("/proc/self/statm", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0;
  char text[128] = {};
  const ssize_t got = ::read(fd, text, sizeof text - 1);
  ::close(fd);
  if (got <= 0) return 0;
  std::size_t pages = 0;
  for (ssize_t i = 0; i < got && text[i] >= '0' && text[i] <= '9'; ++i) {
    pages = pages * 10 + static_cast<std::size_t>(text[i] - '0');
  }
  return pages * static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
}

std::string MiB(std::size_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }

bool ReadAll(int fd, void* data, std::size_t size) {
  auto* bytes = static_cast<char*>(data);
  while (size > 0) {
    const ssize_t got = ::read(fd, bytes, size);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return false;
    bytes += got;
    size -= static_cast<std::size_t>(got);
  }
  return true;
}

// The worker's side: limits, then jobs (an 8-byte index each) until the
// command pipe closes; each answer is a frame: tag, 8-byte length, bytes.
// A job that threw leaves the engine's state untrusted, so the worker
// exits after answering it and the parent starts a fresh one. Never
// returns.
[[noreturn]] void BeWorker(const ProcessLimits& limits, const std::function<std::string(std::size_t)>& work,
                           int commandFd, int answerFd, int stderrFd, std::atomic<int>* stepSlot) {
  ::dup2(stderrFd, STDERR_FILENO);
  ::close(stderrFd);
  ::signal(SIGPIPE, SIG_DFL);  // the parent ignores it; an engine here should not
  // A crashing engine should not spend seconds writing a core file.
  const rlimit noCore{0, 0};
  ::setrlimit(RLIMIT_CORE, &noCore);
  if (limits.memoryBytes > 0) {
    const std::size_t cap = AddressSpaceBytes() + limits.memoryBytes;
    const rlimit memory{cap, cap};
    ::setrlimit(RLIMIT_AS, &memory);
  }
  g_stepSlot = stepSlot;
  std::uint64_t index = 0;
  while (ReadAll(commandFd, &index, sizeof index)) {
    stepSlot->store(kJobNotStepping, std::memory_order_relaxed);
    char tag = kAnswerTag;
    std::string message;
    try {
      message = work(static_cast<std::size_t>(index));
    } catch (const std::bad_alloc& e) {
      tag = kFailureTag;
      message = limits.memoryBytes > 0
                    ? Concat({"ran out of memory (", e.what(), ") within the job's limit of ",
                              MiB(limits.memoryBytes), " (--memory-limit)"})
                    : Concat({"ran out of memory (", e.what(), ")"});
    } catch (const std::exception& e) {
      tag = kFailureTag;
      message = Concat({"threw ", typeid(e).name(), ": ", e.what()});
    } catch (...) {
      tag = kFailureTag;
      message = "threw an exception of unknown type";
    }
    const std::uint64_t size = message.size();
    WriteAll(answerFd, &tag, 1);
    WriteAll(answerFd, reinterpret_cast<const char*>(&size), sizeof size);
    WriteAll(answerFd, message.data(), message.size());
    if (tag == kFailureTag) break;
  }
  ::_exit(0);
}

const char* SignalName(int number) {
  switch (number) {
    case SIGABRT:
      return "SIGABRT";
    case SIGSEGV:
      return "SIGSEGV";
    case SIGBUS:
      return "SIGBUS";
    case SIGFPE:
      return "SIGFPE";
    case SIGILL:
      return "SIGILL";
    case SIGKILL:
      return "SIGKILL";
    case SIGTERM:
      return "SIGTERM";
    case SIGXCPU:
      return "SIGXCPU";
    case SIGTRAP:
      return "SIGTRAP";
    default:
      return "signal";
  }
}

// The last two non-empty lines of `tail`, joined with " / ", at most
// kLastMessageChars (the end kept).
std::string LastLines(const std::string& tail) {
  std::vector<std::string> lines;
  std::size_t end = tail.size();
  while (end > 0 && lines.size() < 2) {
    const std::size_t newline = tail.rfind('\n', end - 1);
    const std::size_t begin = newline == std::string::npos ? 0 : newline + 1;
    std::string line = tail.substr(begin, end - begin);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty()) lines.insert(lines.begin(), std::move(line));
    if (newline == std::string::npos) break;
    end = newline;
  }
  std::string joined;
  for (const std::string& line : lines) joined.append(joined.empty() ? "" : " / ").append(line);
  if (joined.size() > kLastMessageChars) joined = "..." + joined.substr(joined.size() - kLastMessageChars);
  return joined;
}

// One worker process and the job it is running.
struct Worker {
  pid_t pid = -1;
  int commandFd = -1;  // ours to write job indices to
  int answerFd = -1;
  int stderrFd = -1;
  std::size_t slot = 0;
  bool busy = false;
  bool retiring = false;  // sent no more jobs: it exits after its answer
  std::size_t job = 0;
  Clock::time_point started;
  bool killedForTime = false;
  std::string answer;
  std::string stderrLine;  // the part of a line not yet passed on
  std::string stderrTail;  // of the current job
};

// The shared page of step slots, one per worker.
class StepSlots {
 public:
  explicit StepSlots(std::size_t count)
      : m_bytes(std::max<std::size_t>(1, count) * sizeof(std::atomic<int>)) {
    void* memory = ::mmap(nullptr, m_bytes, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (memory == MAP_FAILED) {
      throw std::runtime_error(Concat({"mmap of the step page: ", std::strerror(errno)}));
    }
    m_slots = static_cast<std::atomic<int>*>(memory);
    for (std::size_t i = 0; i < count; ++i) new (&m_slots[i]) std::atomic<int>(kJobNotStepping);
  }
  ~StepSlots() { ::munmap(m_slots, m_bytes); }
  StepSlots(const StepSlots&) = delete;
  StepSlots& operator=(const StepSlots&) = delete;
  std::atomic<int>& operator[](std::size_t i) { return m_slots[i]; }

 private:
  std::size_t m_bytes;
  std::atomic<int>* m_slots = nullptr;
};

void CloseFd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

// SIGPIPE ignored while the pool runs (a job index written to a worker
// that just died must be an error, not the end of the runner), restored
// after.
class IgnoreSigpipe {
 public:
  IgnoreSigpipe() {
    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    ::sigemptyset(&ignore.sa_mask);
    ::sigaction(SIGPIPE, &ignore, &m_old);
  }
  ~IgnoreSigpipe() { ::sigaction(SIGPIPE, &m_old, nullptr); }
  IgnoreSigpipe(const IgnoreSigpipe&) = delete;
  IgnoreSigpipe& operator=(const IgnoreSigpipe&) = delete;

 private:
  struct sigaction m_old {};
};

// Kills and reaps whatever is still running when the pool leaves early
// (an exception from `done`), so no worker outlives the call.
class Reaper {
 public:
  explicit Reaper(std::vector<Worker>& workers) : m_workers(workers) {}
  ~Reaper() {
    for (Worker& worker : m_workers) {
      if (worker.pid > 0) {
        ::kill(worker.pid, SIGKILL);
        ForgetWorker(worker.pid);
        int status = 0;
        while (::waitpid(worker.pid, &status, 0) < 0 && errno == EINTR) {
        }
      }
      CloseFd(worker.commandFd);
      CloseFd(worker.answerFd);
      CloseFd(worker.stderrFd);
    }
  }
  Reaper(const Reaper&) = delete;
  Reaper& operator=(const Reaper&) = delete;

 private:
  std::vector<Worker>& m_workers;
};

// Passes complete lines of a worker's stderr on to ours (whole lines, so
// workers do not cut into each other's lines) and keeps the tail.
void TakeStderr(Worker& worker, const char* data, std::size_t size) {
  worker.stderrTail.append(data, size);
  if (worker.stderrTail.size() > 2 * kStderrTail) {
    worker.stderrTail.erase(0, worker.stderrTail.size() - kStderrTail);
  }
  worker.stderrLine.append(data, size);
  const std::size_t lastNewline = worker.stderrLine.rfind('\n');
  if (lastNewline == std::string::npos) return;
  WriteAll(STDERR_FILENO, worker.stderrLine.data(), lastNewline + 1);
  worker.stderrLine.erase(0, lastNewline + 1);
}

// Reads what `fd` holds now (non-blocking); false at its end.
bool Drain(int fd, std::vector<char>& buffer, const std::function<void(const char*, std::size_t)>& take) {
  while (true) {
    const ssize_t got = ::read(fd, buffer.data(), buffer.size());
    if (got > 0) {
      take(buffer.data(), static_cast<std::size_t>(got));
      continue;
    }
    if (got < 0 && errno == EINTR) continue;
    return got < 0;  // EAGAIN: open, empty now; 0: closed
  }
}

// How a worker's death ended its job; `usage` is the worker's, from wait4.
// Under a memory limit a signal is most likely the limit: an engine whose
// allocator does not handle a failed allocation (Bullet's) dereferences
// the null it got and dies by SIGSEGV (or aborts) instead of throwing
// std::bad_alloc. Only likely, as a crash can have other causes, so the
// message says so and gives the worker's peak resident memory beside the
// limit (which caps address space, so the peak may be well below it).
std::string DeathReason(const Worker& worker, int status, const rusage& usage, const ProcessLimits& limits) {
  if (worker.killedForTime) {
    return Concat({"wall-clock budget spent: the runner killed the job's process after ",
                   FormatNumber(limits.killAfterSeconds), " s"});
  }
  if (WIFSIGNALED(status)) {
    const int number = WTERMSIG(status);
    std::string reason = Concat({"stopped by signal ", std::to_string(number), " (", SignalName(number), ": ",
                                 ::strsignal(number), ")"});
    if (limits.memoryBytes > 0) {
      // ru_maxrss is in KiB on Linux.
      const auto peak = static_cast<std::size_t>(std::max(usage.ru_maxrss, 0L)) << 10;
      reason += Concat(
          {"; the job ran under a memory limit of ", MiB(limits.memoryBytes),
           " (--memory-limit) and likely ran out of memory (its process's peak resident memory: ", MiB(peak),
           "; the limit caps address space)"});
    }
    return reason;
  }
  if (WIFEXITED(status)) {
    return Concat(
        {"the job's process exited with status ", std::to_string(WEXITSTATUS(status)), " and no answer"});
  }
  return "the job's process ended in an unknown way";
}

using Work = std::function<std::string(std::size_t)>;
using Done = std::function<void(std::size_t, JobOutcome)>;

// The pool of RunInChildProcesses: `slots` workers, jobs handed out in
// index order as workers come free, each outcome passed to `done` as its
// answer or its worker's death arrives. Members are declared in the order
// they must be built and torn down: SIGPIPE ignored first and restored
// last, then the terminating signals' handler (worker_signals.h: no worker
// outlives a SIGTERM to the parent), the Reaper after the workers it kills.
class WorkerPool {
 public:
  WorkerPool(std::size_t count, std::size_t slots, const ProcessLimits& limits, const Work& work,
             const Done& done)
      : m_count(count),
        m_limits(limits),
        m_work(work),
        m_done(done),
        m_steps(slots),
        m_workers(slots),
        m_reaper(m_workers),
        m_buffer(1 << 16) {}

  // Until every job has its outcome and every worker is buried.
  void Run() {
    while (m_finished < m_count || AnyWorkerAlive()) {
      for (std::size_t slot = 0; slot < m_workers.size(); ++slot) Feed(slot);
      if (!WaitAndRead(MillisecondsToNearestLimit())) continue;
      KillOverdue();
    }
  }

 private:
  bool AnyWorkerAlive() const {
    return std::any_of(m_workers.begin(), m_workers.end(), [](const Worker& w) { return w.pid > 0; });
  }

  // Counts the job as finished and hands its outcome on.
  void Finish(std::size_t job, JobOutcome outcome) {
    ++m_finished;
    m_done(job, std::move(outcome));
  }

  std::string StartWorker(std::size_t slot);
  void Feed(std::size_t slot);
  void Bury(std::size_t slot);
  void TakeAnswers(std::size_t slot);
  int MillisecondsToNearestLimit() const;
  bool WaitAndRead(int timeoutMs);
  void KillOverdue();

  const std::size_t m_count;
  const ProcessLimits& m_limits;
  const Work& m_work;
  const Done& m_done;
  const IgnoreSigpipe m_sigpipe;
  const WorkerSignalGuard m_signals;
  StepSlots m_steps;
  std::vector<Worker> m_workers;
  const Reaper m_reaper;
  std::vector<char> m_buffer;
  std::size_t m_next = 0;      // the next job to hand out
  std::size_t m_finished = 0;  // jobs whose outcome went to `done`
  std::vector<pollfd> m_polled;
  std::vector<std::size_t> m_polledSlot;
};

// Starts the worker of `slot`; the reason when a pipe or the fork failed.
std::string WorkerPool::StartWorker(std::size_t slot) {
  int command[2];
  int answer[2];
  int err[2];
  if (::pipe2(command, O_CLOEXEC) != 0) return Concat({"pipe: ", std::strerror(errno)});
  if (::pipe2(answer, O_CLOEXEC) != 0) {
    const std::string reason = Concat({"pipe: ", std::strerror(errno)});
    ::close(command[0]);
    ::close(command[1]);
    return reason;
  }
  if (::pipe2(err, O_CLOEXEC) != 0) {
    const std::string reason = Concat({"pipe: ", std::strerror(errno)});
    for (int fd : {command[0], command[1], answer[0], answer[1]}) ::close(fd);
    return reason;
  }
  // No terminating signal between the fork and the new pid's record, so
  // the handler never misses a worker (worker_signals.h).
  BlockTerminatingSignals blocked;
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    BecomeWorkerProcess(parent, blocked.Old());
    // The other workers' pipe ends must not stay open here: a worker
    // holding another's command pipe would keep it from ever seeing its end.
    for (Worker& other : m_workers) {
      for (int fd : {other.commandFd, other.answerFd, other.stderrFd}) {
        if (fd >= 0) ::close(fd);
      }
    }
    ::close(command[1]);
    ::close(answer[0]);
    ::close(err[0]);
    BeWorker(m_limits, m_work, command[0], answer[1], err[1], &m_steps[slot]);
  }
  if (pid > 0) RecordWorker(pid);
  ::close(command[0]);
  ::close(answer[1]);
  ::close(err[1]);
  if (pid < 0) {
    const std::string reason = Concat({"fork: ", std::strerror(errno)});
    for (int fd : {command[1], answer[0], err[0]}) ::close(fd);
    return reason;
  }
  ::fcntl(answer[0], F_SETFL, O_NONBLOCK);
  ::fcntl(err[0], F_SETFL, O_NONBLOCK);
  Worker& worker = m_workers[slot];
  worker = Worker{};
  worker.pid = pid;
  worker.commandFd = command[1];
  worker.answerFd = answer[0];
  worker.stderrFd = err[0];
  worker.slot = slot;
  return {};
}

// Hands the next job to an idle worker of `slot` (starting it if need
// be), or lets it retire when none is left.
void WorkerPool::Feed(std::size_t slot) {
  Worker& worker = m_workers[slot];
  if (worker.busy || worker.retiring) return;
  if (m_next == m_count) {
    if (worker.pid > 0) {
      worker.retiring = true;
      CloseFd(worker.commandFd);
    }
    return;
  }
  if (worker.pid <= 0) {
    if (const std::string refused = StartWorker(slot); !refused.empty()) {
      JobOutcome outcome;
      outcome.failure = Concat({"could not start the job's process: ", refused});
      Finish(m_next++, std::move(outcome));
      return;
    }
  }
  const std::uint64_t index = m_next;
  worker.busy = true;
  worker.job = m_next++;
  worker.started = Clock::now();
  worker.killedForTime = false;
  worker.stderrTail.clear();
  m_steps[slot].store(kJobNotStepping, std::memory_order_relaxed);
  // A worker that died since its last answer shows as EPIPE here and as
  // the end of its answer pipe below, which ends this job with its cause.
  WriteAll(worker.commandFd, reinterpret_cast<const char*>(&index), sizeof index);
}

// The worker of `slot` has ended (its answer pipe closed): its job, if
// any, ends with the cause; the slot is free for a new worker.
void WorkerPool::Bury(std::size_t slot) {
  Worker& worker = m_workers[slot];
  if (worker.stderrFd >= 0) {
    // Blocking now: the worker is gone or going, its stderr ends with it.
    ::fcntl(worker.stderrFd, F_SETFL, 0);
    Drain(worker.stderrFd, m_buffer,
          [&](const char* data, std::size_t size) { TakeStderr(worker, data, size); });
    CloseFd(worker.stderrFd);
  }
  if (!worker.stderrLine.empty()) {
    worker.stderrLine.push_back('\n');
    WriteAll(STDERR_FILENO, worker.stderrLine.data(), worker.stderrLine.size());
    worker.stderrLine.clear();
  }
  int status = 0;
  rusage usage{};
  ForgetWorker(worker.pid);  // before the pid is freed for reuse
  while (::wait4(worker.pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  CloseFd(worker.commandFd);
  CloseFd(worker.answerFd);
  const bool wasBusy = worker.busy;
  JobOutcome outcome;
  if (wasBusy) {
    outcome.failure = DeathReason(worker, status, usage, m_limits);
    outcome.killedForTime = worker.killedForTime;
    outcome.step = m_steps[slot].load(std::memory_order_relaxed);
    outcome.lastMessage = LastLines(worker.stderrTail);
    outcome.wallSeconds = std::chrono::duration<double>(Clock::now() - worker.started).count();
  }
  const std::size_t job = worker.job;
  worker = Worker{};
  if (wasBusy) Finish(job, std::move(outcome));
}

// Complete answer frames in a worker's buffer go to `done`.
void WorkerPool::TakeAnswers(std::size_t slot) {
  Worker& worker = m_workers[slot];
  constexpr std::size_t kHeader = 1 + sizeof(std::uint64_t);
  while (worker.busy && worker.answer.size() >= kHeader) {
    std::uint64_t size = 0;
    std::memcpy(&size, worker.answer.data() + 1, sizeof size);
    if (worker.answer.size() - kHeader < size) return;
    // Its stderr was written before its answer: take all of it first.
    if (worker.stderrFd >= 0) {
      Drain(worker.stderrFd, m_buffer, [&](const char* data, std::size_t n) { TakeStderr(worker, data, n); });
    }
    JobOutcome outcome;
    outcome.wallSeconds = std::chrono::duration<double>(Clock::now() - worker.started).count();
    outcome.step = m_steps[slot].load(std::memory_order_relaxed);
    const std::string body = worker.answer.substr(kHeader, static_cast<std::size_t>(size));
    if (worker.answer[0] == kAnswerTag) {
      outcome.finished = true;
      outcome.answer = body;
    } else {
      outcome.failure = body;
      outcome.lastMessage = LastLines(worker.stderrTail);
      worker.retiring = true;  // it exits after a failed job
      CloseFd(worker.commandFd);
    }
    worker.answer.erase(0, kHeader + static_cast<std::size_t>(size));
    worker.busy = false;
    Finish(worker.job, std::move(outcome));
  }
}

// How long poll may wait: until the nearest busy worker's time limit
// (at least 0 ms), or for ever (-1) without a limit or a busy worker.
int WorkerPool::MillisecondsToNearestLimit() const {
  int timeoutMs = -1;
  if (m_limits.killAfterSeconds <= 0.0) return timeoutMs;
  const auto now = Clock::now();
  for (const Worker& worker : m_workers) {
    if (!worker.busy || worker.killedForTime) continue;
    const double left =
        m_limits.killAfterSeconds - std::chrono::duration<double>(now - worker.started).count();
    const int ms = left <= 0.0 ? 0 : static_cast<int>(std::min(left * 1000.0 + 1.0, 1e9));
    timeoutMs = timeoutMs < 0 ? ms : std::min(timeoutMs, ms);
  }
  return timeoutMs;
}

// Waits for output from any worker or `timeoutMs`, then passes stderr on,
// takes complete answers and buries workers whose answer pipe closed.
// False when no worker has a pipe open (nothing to wait for).
bool WorkerPool::WaitAndRead(int timeoutMs) {
  m_polled.clear();
  m_polledSlot.clear();
  for (std::size_t slot = 0; slot < m_workers.size(); ++slot) {
    const Worker& worker = m_workers[slot];
    if (worker.answerFd >= 0) {
      m_polled.push_back({worker.answerFd, POLLIN, 0});
      m_polledSlot.push_back(slot);
    }
    if (worker.stderrFd >= 0) {
      m_polled.push_back({worker.stderrFd, POLLIN, 0});
      m_polledSlot.push_back(slot);
    }
  }
  if (m_polled.empty()) return false;
  if (::poll(m_polled.data(), m_polled.size(), timeoutMs) < 0 && errno != EINTR) {
    throw std::runtime_error(Concat({"poll: ", std::strerror(errno)}));
  }
  for (std::size_t i = 0; i < m_polled.size(); ++i) {
    if (m_polled[i].revents == 0) continue;
    const std::size_t slot = m_polledSlot[i];
    Worker& worker = m_workers[slot];
    if (m_polled[i].fd == worker.stderrFd) {
      const bool open = Drain(worker.stderrFd, m_buffer,
                              [&](const char* data, std::size_t n) { TakeStderr(worker, data, n); });
      if (!open) CloseFd(worker.stderrFd);
    } else if (m_polled[i].fd == worker.answerFd) {
      const bool open = Drain(worker.answerFd, m_buffer,
                              [&](const char* data, std::size_t n) { worker.answer.append(data, n); });
      TakeAnswers(slot);
      if (!open) Bury(slot);
    }
  }
  return true;
}

// The time limit: kill; the answer pipe then closes and the worker is
// buried by the next WaitAndRead.
void WorkerPool::KillOverdue() {
  if (m_limits.killAfterSeconds <= 0.0) return;
  const auto later = Clock::now();
  for (Worker& worker : m_workers) {
    if (worker.busy && !worker.killedForTime &&
        std::chrono::duration<double>(later - worker.started).count() >= m_limits.killAfterSeconds) {
      worker.killedForTime = true;
      ::kill(worker.pid, SIGKILL);
    }
  }
}

}  // namespace

void ReportJobStep(int step) {
  if (g_stepSlot != nullptr) g_stepSlot->store(step, std::memory_order_relaxed);
}

void RunInChildProcesses(std::size_t count, int parallel, const ProcessLimits& limits, const Work& work,
                         const Done& done) {
  const std::size_t slots = std::min<std::size_t>(static_cast<std::size_t>(std::max(1, parallel)), count);
  if (slots == 0) return;
  WorkerPool pool(count, slots, limits, work, done);
  pool.Run();
}

}  // namespace talus::harness
