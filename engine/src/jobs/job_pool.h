// JobPool: the engine's threads. A fixed set of worker threads that run one
// ParallelFor (or one chain of them, RunPhases) at a time, with the calling thread working alongside them.
//
// Determinism is the design constraint, not speed: World::Step must give the
// same bits for any thread count. So the pool never decides *what* is
// computed, only *who* computes it. ParallelFor(count, grain, fn) cuts
// [0, count) into chunks of `grain` items (the last one shorter); the chunk
// boundaries depend on count and grain alone, never on the thread count.
// A caller that writes each item's result into its own slot, and reduces
// per-chunk partial results in chunk order afterwards, gets the same answer
// with 1 thread or 64. Threads claim the next chunk from one atomic counter
// (dynamic assignment): on a machine shared with other work, a thread that
// is descheduled simply claims fewer chunks, where a static split would
// leave everyone waiting for it.
//
// With one thread no worker is started and ParallelFor runs the same chunks
// in order on the caller: the single-threaded step pays no synchronisation.
//
// Alternatives rejected: oneTBB and OpenMP (both in Debian, both good) would
// add a run-time dependency to an engine that promises Eigen and the
// standard library only, and neither is needed for one loop shape; a
// work-stealing deque pays for nested and unbalanced task graphs the step
// does not have (every stage is a flat loop).
//
// Phases (RunPhases). A stage that is a chain of loops, each needing the
// previous one finished (the coloured solver's colours, sweep after sweep),
// is one job: the chunks of every phase are numbered in one sequence and
// claimed from the same counter, and a thread claims a chunk of phase p
// only once every chunk of the earlier phases has returned. The wait is on
// finished chunks, not on threads arriving: a thread the system has
// descheduled holds nobody up unless it is running a chunk. One hand-off
// per chain instead of one per loop.
//
// Rules for `fn`: it must not throw (the call is noexcept; an exception
// terminates, as it would in the serial step), it must not call ParallelFor
// on the same pool (a nested call runs its chunks serially on the calling
// thread, which is correct but not parallel), and chunks must not write
// shared state except through their own slots.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <thread>
#include <typeindex>
#include <typeinfo>
#include <vector>

namespace talus {

/// One loop of a RunPhases chain: [0, count) in chunks of `grain` items.
struct JobPhase {
  int count = 0;
  int grain = 1;
};

/// Something that runs a chain of phases as JobPool::RunPhases promises
/// (each phase after the earlier ones, its chunks in any order): a pool, or
/// a test's own cut. Stages that run on threads take one of these rather
/// than the pool, so the same code runs serially when it is empty.
using PhaseRunner =
    std::function<void(std::span<const JobPhase> phases, const std::function<void(int, int, int)>& fn)>;

/// `runner` if set, else every chunk of every phase in order on this thread.
void RunPhasesWith(const PhaseRunner& runner, std::span<const JobPhase> phases,
                   const std::function<void(int phase, int begin, int end)>& fn);

/// Number of chunks ParallelFor cuts `count` items into at `grain` items
/// per chunk (grain < 1 counts as 1). Chunk c is [c grain, min(count, (c+1) grain)).
[[nodiscard]] int ChunkCount(int count, int grain);

/// fn(begin, end) for every chunk of [0, count) (as ChunkCount cuts it), in
/// order, on this thread.
template <class Fn>
void ForEachChunkInOrder(int count, int grain, Fn&& fn) {
  const int g = grain < 1 ? 1 : grain;
  for (int begin = 0; begin < count; begin += g) fn(begin, count - begin < g ? count : begin + g);
}

class JobPool {
 public:
  /// A pool that runs ParallelFor on `threads` threads, the caller included
  /// (so threads - 1 workers are started; none for 1). `threads` must be
  /// >= 1 (asserted; WorldSettings validation refuses others).
  /// Starting a thread can fail (std::system_error); the constructor then
  /// stops the workers already started and rethrows, leaving nothing behind.
  explicit JobPool(int threads = 1);
  ~JobPool();
  JobPool(const JobPool&) = delete;
  JobPool& operator=(const JobPool&) = delete;

  /// Threads that run a ParallelFor, the caller included.
  [[nodiscard]] int ThreadCount() const { return static_cast<int>(m_workers.size()) + 1; }

  /// Calls fn(begin, end) once for every chunk of [0, count) (see
  /// ChunkCount), on any of the pool's threads, and returns when all have
  /// returned. Chunks may run in any order and at the same time. count <= 0
  /// calls nothing. With one thread the chunks run in order right here,
  /// with no std::function, lock or allocation in between: a small world's
  /// step makes five of these calls, and wrapping them cost more than a
  /// two-body step's integration (perf, sphere_bounce_series).
  template <class Fn>
  void ParallelFor(int count, int grain, Fn&& fn) noexcept {
    if (m_workers.empty()) {
      ForEachChunkInOrder(count, grain, fn);
    } else {
      ParallelForOnWorkers(count, grain, fn);
    }
  }

  /// ParallelFor whose fn(thread, begin, end) also gets the index of the
  /// pool thread running the chunk, in [0, ThreadCount()): 0 is the calling
  /// thread, worker i is i + 1. It picks the thread's scratch
  /// (ThreadScratch); which thread runs which chunk varies run to run, so
  /// nothing but scratch may depend on it. Must not be called from inside a
  /// chunk of this pool (a nested call runs on the calling thread, whose
  /// index it cannot know).
  template <class Fn>
  void ParallelForOnThreads(int count, int grain, Fn&& fn) noexcept {
    if (m_workers.empty()) {
      ForEachChunkInOrder(count, grain, [&fn](int begin, int end) { fn(0, begin, end); });
    } else {
      ParallelForOnWorkersIndexed(count, grain, fn);
    }
  }

  /// One T per pool thread, indexed as ParallelForOnThreads numbers them:
  /// working memory a chunk may use without sharing it, owned by the pool
  /// and kept (capacity included) as long as it lives, so steady-state
  /// steps allocate nothing. Made on the first call for T; call it outside
  /// the pool's chunks.
  template <class T>
  std::span<T> ThreadScratch() {
    const std::size_t threads = static_cast<std::size_t>(ThreadCount());
    for (const ScratchSlot& slot : m_scratch) {
      if (slot.type == std::type_index(typeid(T))) return {static_cast<T*>(slot.items.get()), threads};
    }
    std::shared_ptr<void> items(new T[threads], [](void* p) { delete[] static_cast<T*>(p); });
    m_scratch.push_back({std::type_index(typeid(T)), items});
    return {static_cast<T*>(items.get()), threads};
  }

  /// Runs the loops `phases` one after the other: fn(p, begin, end) once for
  /// every chunk of phase p (chunks as ParallelFor's), where every chunk of
  /// phases 0 .. p-1 has returned before any chunk of phase p starts (and
  /// its writes are visible to it). Chunks of one phase may run at once, in
  /// any order, on any thread. Returns when the last phase is done. Phases
  /// with no items are skipped.
  void RunPhases(std::span<const JobPhase> phases,
                 const std::function<void(int phase, int begin, int end)>& fn) noexcept;

 private:
  // One RunPhases call, copied by each worker that joins it. The chunks of
  // all phases are numbered 0 .. chunks - 1 in phase order; phase p holds
  // [m_phaseFirst[p], m_phaseFirst[p + 1]).
  struct Job {
    const std::function<void(int, int, int, int)>* fn = nullptr;  // (thread, phase, begin, end)
    const JobPhase* phases = nullptr;
    const int* phaseFirst = nullptr;
    int phaseCount = 0;
    int chunks = 0;
  };

  // ParallelFor with workers to share the chunks.
  void ParallelForOnWorkers(int count, int grain, const std::function<void(int begin, int end)>& fn) noexcept;
  void ParallelForOnWorkersIndexed(int count, int grain,
                                   const std::function<void(int thread, int begin, int end)>& fn) noexcept;
  // RunPhases with the running thread's index passed to fn first.
  void RunPhasesOnThreads(std::span<const JobPhase> phases,
                          const std::function<void(int thread, int phase, int begin, int end)>& fn) noexcept;
  // Worker `thread` (1 .. ThreadCount() - 1).
  void WorkerLoop(int thread);
  // Runs the chunk of phase `phase` numbered `chunk` in the whole job, on
  // pool thread `thread`.
  static void RunChunk(const Job& job, int thread, int phase, int chunk) noexcept;
  // Claims and runs chunks of `job` on pool thread `thread` until none is
  // left, each after the earlier phases are done.
  void RunChunks(const Job& job, int thread) noexcept;

  // One ThreadScratch array: its element type and ThreadCount() items.
  struct ScratchSlot {
    std::type_index type;
    std::shared_ptr<void> items;
  };
  // Waits until at least `chunks` chunks of the current job have returned.
  void AwaitDone(int chunks) noexcept;

  std::vector<std::thread> m_workers;
  std::vector<ScratchSlot> m_scratch;  // ThreadScratch's arrays, by type
  std::vector<int> m_phaseFirst;       // the current job's phase starts, written under m_mutex

  Job m_job;                                   // the current job, guarded by m_mutex
  std::atomic<int> m_nextChunk{0};             // next chunk to claim
  std::atomic<int> m_doneChunks{0};            // chunks that have returned
  std::atomic<std::uint64_t> m_generation{0};  // bumped per job (written under m_mutex)

  std::mutex m_mutex;
  std::condition_variable m_wake;  // workers: a new job or stop
  std::condition_variable m_done;  // caller: every chunk ran, or every worker left the job
  int m_busyWorkers = 0;           // workers inside a job, guarded by m_mutex
  bool m_running = false;          // a ParallelFor is in progress, guarded by m_mutex
  bool m_stop = false;             // guarded by m_mutex
};

}  // namespace talus
