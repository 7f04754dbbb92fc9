// The engine's thread pool; see jobs/job_pool.h for the design.
//
// Hand-off protocol (all job fields are written under m_mutex):
//   caller:  wait until no worker is still inside the previous job, write the
//            job, reset the counters, bump m_generation, wake the workers,
//            claim chunks itself, then wait until every chunk has run.
//   worker:  sleep until m_generation changes, copy the job under the mutex,
//            claim chunks until none is left, leave the job.
// A RunPhases job numbers the chunks of all its phases in one sequence; a
// thread claims the next chunk (compare-exchange on m_nextChunk) only once
// m_doneChunks has reached the first chunk of its phase (every earlier
// chunk returned; the fetch_add that counted each one releases its writes
// to the thread that reads the count). A waiting thread holds no chunk, so
// the wait cannot deadlock and a descheduled waiter delays nobody: the
// chunks waited on are all held by threads that are running them.
// A worker that wakes late (after the job's chunks are all taken) claims
// nothing and never touches the caller's function. Because the next job
// waits for every worker to leave the previous one, the chunk counter is
// never reset under a worker still claiming from it.
//
// Waiting spins briefly before it blocks: a step issues several
// ParallelFor calls a few hundred microseconds apart, and waking a blocked
// thread costs tens of microseconds. The spin is short (about a few
// microseconds of pause instructions) so a machine with more threads than
// cores loses little to it.
#include "jobs/job_pool.h"

#include <cassert>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace talus {
namespace {

// Polls before blocking (each a pause instruction, ~40 cycles or more).
constexpr int kSpinPolls = 2000;

void CpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

}  // namespace

int ChunkCount(int count, int grain) {
  if (count <= 0) return 0;
  const int g = grain < 1 ? 1 : grain;
  return count / g + (count % g != 0 ? 1 : 0);
}

void RunPhasesWith(const PhaseRunner& runner, std::span<const JobPhase> phases,
                   const std::function<void(int, int, int)>& fn) {
  if (runner) {
    runner(phases, fn);
    return;
  }
  for (std::size_t p = 0; p < phases.size(); ++p) {
    const int phase = static_cast<int>(p);
    ForEachChunkInOrder(phases[p].count, phases[p].grain,
                        [&fn, phase](int begin, int end) { fn(phase, begin, end); });
  }
}

JobPool::JobPool(int threads) {
  assert(threads >= 1);
  const int workers = threads < 1 ? 0 : threads - 1;
  m_workers.reserve(static_cast<std::size_t>(workers));
  try {
    for (int i = 0; i < workers; ++i) m_workers.emplace_back([this, i] { WorkerLoop(i + 1); });
  } catch (...) {
    // Stop what was started, then report the failure to the caller.
    {
      const std::lock_guard lock(m_mutex);
      m_stop = true;
    }
    m_wake.notify_all();
    for (std::thread& worker : m_workers) worker.join();
    throw;
  }
}

JobPool::~JobPool() {
  {
    const std::lock_guard lock(m_mutex);
    m_stop = true;
    m_generation.fetch_add(1);
  }
  m_wake.notify_all();
  for (std::thread& worker : m_workers) worker.join();
}

void JobPool::ParallelForOnWorkers(int count, int grain, const std::function<void(int, int)>& fn) noexcept {
  const JobPhase phase{.count = count, .grain = grain};
  RunPhasesOnThreads(std::span<const JobPhase>(&phase, 1),
                     [&fn](int, int, int begin, int end) { fn(begin, end); });
}

void JobPool::ParallelForOnWorkersIndexed(int count, int grain,
                                          const std::function<void(int, int, int)>& fn) noexcept {
  const JobPhase phase{.count = count, .grain = grain};
  RunPhasesOnThreads(std::span<const JobPhase>(&phase, 1),
                     [&fn](int thread, int, int begin, int end) { fn(thread, begin, end); });
}

void JobPool::RunPhases(std::span<const JobPhase> phases,
                        const std::function<void(int, int, int)>& fn) noexcept {
  RunPhasesOnThreads(phases, [&fn](int, int phase, int begin, int end) { fn(phase, begin, end); });
}

void JobPool::RunPhasesOnThreads(std::span<const JobPhase> phases,
                                 const std::function<void(int, int, int, int)>& fn) noexcept {
  int chunks = 0;
  for (const JobPhase& phase : phases) chunks += ChunkCount(phase.count, phase.grain);
  if (chunks == 0) return;
  Job job;
  {
    std::unique_lock lock(m_mutex);
    // No workers, a single chunk, or a call from inside a job: the same
    // chunks, in order, on this thread.
    if (m_workers.empty() || chunks == 1 || m_running) {
      lock.unlock();
      RunPhasesWith(nullptr, phases, [&fn](int phase, int begin, int end) { fn(0, phase, begin, end); });
      return;
    }
    m_done.wait(lock, [this] { return m_busyWorkers == 0; });
    m_phaseFirst.assign(1, 0);
    for (const JobPhase& phase : phases) {
      m_phaseFirst.push_back(m_phaseFirst.back() + ChunkCount(phase.count, phase.grain));
    }
    job = Job{.fn = &fn,
              .phases = phases.data(),
              .phaseFirst = m_phaseFirst.data(),
              .phaseCount = static_cast<int>(phases.size()),
              .chunks = chunks};
    m_job = job;
    m_nextChunk.store(0);
    m_doneChunks.store(0);
    m_running = true;
    m_generation.fetch_add(1);
  }
  m_wake.notify_all();
  RunChunks(job, 0);
  for (int poll = 0; poll < kSpinPolls && m_doneChunks.load() != chunks; ++poll) CpuRelax();
  std::unique_lock lock(m_mutex);
  m_done.wait(lock, [this, chunks] { return m_doneChunks.load() == chunks; });
  m_running = false;
}

void JobPool::RunChunk(const Job& job, int thread, int phase, int chunk) noexcept {
  const JobPhase& p = job.phases[phase];
  const int g = p.grain < 1 ? 1 : p.grain;
  const int begin = (chunk - job.phaseFirst[phase]) * g;
  const int end = p.count - begin < g ? p.count : begin + g;
  (*job.fn)(thread, phase, begin, end);
}

void JobPool::AwaitDone(int chunks) noexcept {
  // Spin first (the other threads are usually a few chunks from the end of
  // the phase), then sleep on the counter (a futex): on a machine with more
  // runnable threads than cores, the thread holding the last chunk of the
  // phase may be waiting for this core, and polling would take it.
  for (int poll = 0; poll < kSpinPolls; ++poll) {
    if (m_doneChunks.load() >= chunks) return;
    CpuRelax();
  }
  for (int seen = m_doneChunks.load(); seen < chunks; seen = m_doneChunks.load()) m_doneChunks.wait(seen);
}

void JobPool::RunChunks(const Job& job, int thread) noexcept {
  int phase = 0;
  int chunk = m_nextChunk.load();
  for (;;) {
    if (chunk >= job.chunks) return;
    while (chunk >= job.phaseFirst[phase + 1]) ++phase;
    // Claim a chunk only once its phase is open (every chunk of the earlier
    // phases returned), so a waiting thread holds no chunk: if the system
    // deschedules it while it waits, the others run the phase without it.
    // Claiming first and waiting after would leave its chunk unrun until
    // it is scheduled again, and the next phase waiting on that.
    if (m_doneChunks.load() < job.phaseFirst[phase]) {
      AwaitDone(job.phaseFirst[phase]);
      chunk = m_nextChunk.load();
      continue;
    }
    if (!m_nextChunk.compare_exchange_weak(chunk, chunk + 1)) continue;  // `chunk` reloaded
    RunChunk(job, thread, phase, chunk);
    const int done = m_doneChunks.fetch_add(1) + 1;
    // Wake the threads sleeping in AwaitDone (a no-op without sleepers).
    if (job.phaseCount > 1) m_doneChunks.notify_all();
    if (done == job.chunks) {
      // The last chunk: wake the caller (under the mutex, so the wake-up
      // cannot fall between its check and its wait).
      const std::lock_guard lock(m_mutex);
      m_done.notify_all();
    }
    chunk = m_nextChunk.load();
  }
}

void JobPool::WorkerLoop(int thread) {
  std::uint64_t seen = 0;
  for (;;) {
    for (int poll = 0; poll < kSpinPolls && m_generation.load() == seen; ++poll) CpuRelax();
    Job job;
    {
      std::unique_lock lock(m_mutex);
      m_wake.wait(lock, [this, seen] { return m_stop || m_generation.load() != seen; });
      if (m_stop) return;
      seen = m_generation.load();
      job = m_job;
      ++m_busyWorkers;
    }
    RunChunks(job, thread);
    {
      const std::lock_guard lock(m_mutex);
      if (--m_busyWorkers == 0) m_done.notify_all();
    }
  }
}

}  // namespace talus
