// The engine's thread pool; see jobs/job_pool.h for the design.
//
// Hand-off protocol (all job fields are written under m_mutex):
//   caller:  wait until no worker is still inside the previous job, write the
//            job, reset the counters, bump m_generation, wake the workers,
//            claim chunks itself, then wait until every chunk has run.
//   worker:  sleep until m_generation changes, copy the job under the mutex,
//            claim chunks until none is left, leave the job.
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

JobPool::JobPool(int threads) {
  assert(threads >= 1);
  const int workers = threads < 1 ? 0 : threads - 1;
  m_workers.reserve(static_cast<std::size_t>(workers));
  try {
    for (int i = 0; i < workers; ++i) m_workers.emplace_back([this] { WorkerLoop(); });
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

void JobPool::ParallelFor(int count, int grain, const std::function<void(int, int)>& fn) noexcept {
  const int chunks = ChunkCount(count, grain);
  if (chunks == 0) return;
  const int g = grain < 1 ? 1 : grain;
  const Job job{.fn = &fn, .count = count, .grain = g, .chunks = chunks};
  {
    std::unique_lock lock(m_mutex);
    // No workers, a single chunk, or a call from inside a job: the same
    // chunks, in order, on this thread.
    if (m_workers.empty() || chunks == 1 || m_running) {
      lock.unlock();
      for (int c = 0; c < chunks; ++c) RunChunk(job, c);
      return;
    }
    m_done.wait(lock, [this] { return m_busyWorkers == 0; });
    m_job = job;
    m_nextChunk.store(0);
    m_doneChunks.store(0);
    m_running = true;
    m_generation.fetch_add(1);
  }
  m_wake.notify_all();
  RunChunks(job);
  for (int poll = 0; poll < kSpinPolls && m_doneChunks.load() != chunks; ++poll) CpuRelax();
  std::unique_lock lock(m_mutex);
  m_done.wait(lock, [this, chunks] { return m_doneChunks.load() == chunks; });
  m_running = false;
}

void JobPool::RunChunk(const Job& job, int chunk) noexcept {
  const int begin = chunk * job.grain;
  const int end = job.count - begin < job.grain ? job.count : begin + job.grain;
  (*job.fn)(begin, end);
}

void JobPool::RunChunks(const Job& job) noexcept {
  for (;;) {
    const int chunk = m_nextChunk.fetch_add(1);
    if (chunk >= job.chunks) return;
    RunChunk(job, chunk);
    if (m_doneChunks.fetch_add(1) + 1 == job.chunks) {
      // The last chunk: wake the caller (under the mutex, so the wake-up
      // cannot fall between its check and its wait).
      const std::lock_guard lock(m_mutex);
      m_done.notify_all();
    }
  }
}

void JobPool::WorkerLoop() {
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
    RunChunks(job);
    {
      const std::lock_guard lock(m_mutex);
      if (--m_busyWorkers == 0) m_done.notify_all();
    }
  }
}

}  // namespace talus
