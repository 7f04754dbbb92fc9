// JobPool (engine/src/jobs): every item visited exactly once, chunk
// boundaries that depend on the count and grain alone, real parallelism,
// nested calls, and many back-to-back jobs (the hand-off ThreadSanitizer
// watches).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <span>
#include <thread>
#include <utility>
#include <vector>

#include "jobs/job_pool.h"

namespace talus {
namespace job_pool_test {

TEST(ChunkCount, CeilingOfCountOverGrain) {
  EXPECT_EQ(ChunkCount(0, 4), 0);
  EXPECT_EQ(ChunkCount(-3, 4), 0);
  EXPECT_EQ(ChunkCount(1, 4), 1);
  EXPECT_EQ(ChunkCount(8, 4), 2);
  EXPECT_EQ(ChunkCount(9, 4), 3);
  EXPECT_EQ(ChunkCount(5, 0), 5);  // a grain below 1 counts as 1
}

// The chunks a ParallelFor ran, sorted: they must be [c g, min(n, (c+1) g))
// for every c, whatever the thread count.
std::vector<std::pair<int, int>> ChunksRun(JobPool& pool, int count, int grain) {
  std::mutex mutex;
  std::vector<std::pair<int, int>> chunks;
  std::vector<std::atomic<int>> visits(static_cast<std::size_t>(std::max(count, 0)));
  pool.ParallelFor(count, grain, [&](int begin, int end) {
    for (int i = begin; i < end; ++i) visits[static_cast<std::size_t>(i)].fetch_add(1);
    const std::lock_guard lock(mutex);
    chunks.emplace_back(begin, end);
  });
  for (int i = 0; i < count; ++i) EXPECT_EQ(visits[static_cast<std::size_t>(i)].load(), 1) << "item " << i;
  std::sort(chunks.begin(), chunks.end());
  return chunks;
}

TEST(JobPool, EveryItemOnceInChunksThatIgnoreTheThreadCount) {
  for (const int threads : {1, 2, 3, 8}) {
    JobPool pool(threads);
    EXPECT_EQ(pool.ThreadCount(), threads);
    for (const int count : {0, 1, 7, 64, 1001}) {
      for (const int grain : {1, 3, 64}) {
        const std::vector<std::pair<int, int>> chunks = ChunksRun(pool, count, grain);
        ASSERT_EQ(static_cast<int>(chunks.size()), ChunkCount(count, grain));
        for (std::size_t c = 0; c < chunks.size(); ++c) {
          const int begin = static_cast<int>(c) * grain;
          EXPECT_EQ(chunks[c].first, begin);
          EXPECT_EQ(chunks[c].second, std::min(count, begin + grain));
        }
      }
    }
  }
}

TEST(JobPool, OneThreadRunsTheChunksInOrderOnTheCaller) {
  JobPool pool(1);
  std::vector<int> begins;
  const std::thread::id caller = std::this_thread::get_id();
  pool.ParallelFor(10, 3, [&](int begin, int) {
    EXPECT_EQ(std::this_thread::get_id(), caller);
    begins.push_back(begin);
  });
  EXPECT_EQ(begins, (std::vector<int>{0, 3, 6, 9}));
}

// The first chunk holds its thread until another chunk has started (or
// 10 s have passed, far beyond any scheduling delay on a loaded machine),
// so a pool that never hands work to a worker fails.
TEST(JobPool, WorkersTakeChunks) {
  JobPool pool(4);
  std::mutex mutex;
  std::set<std::thread::id> ids;
  std::atomic<int> started{0};
  pool.ParallelFor(16, 1, [&](int begin, int) {
    started.fetch_add(1);
    {
      const std::lock_guard lock(mutex);
      ids.insert(std::this_thread::get_id());
    }
    if (begin != 0) return;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (started.load() < 2 && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
  });
  EXPECT_GE(ids.size(), 2u);
}

TEST(JobPool, NestedCallsRunOnTheCallingThread) {
  JobPool pool(3);
  std::vector<std::atomic<int>> visits(40 * 5);
  pool.ParallelFor(40, 2, [&](int begin, int end) {
    for (int i = begin; i < end; ++i) {
      const std::thread::id outer = std::this_thread::get_id();
      pool.ParallelFor(5, 1, [&](int b, int e) {
        EXPECT_EQ(std::this_thread::get_id(), outer);
        for (int j = b; j < e; ++j) visits[static_cast<std::size_t>(i * 5 + j)].fetch_add(1);
      });
    }
  });
  for (const std::atomic<int>& v : visits) EXPECT_EQ(v.load(), 1);
}

// ParallelForOnThreads numbers the pool's threads 0 (the caller) to
// ThreadCount() - 1, one number per thread, so a chunk may use its thread's
// ThreadScratch without a lock: here each chunk appends its items to its
// thread's vector unguarded (ThreadSanitizer watches), and together the
// vectors hold every item once. The scratch stays with the pool.
TEST(JobPool, EachThreadGetsItsOwnScratch) {
  for (const int threads : {1, 4}) {
    JobPool pool(threads);
    const std::span<std::vector<int>> scratch = pool.ThreadScratch<std::vector<int>>();
    ASSERT_EQ(scratch.size(), static_cast<std::size_t>(threads));
    std::mutex mutex;
    std::vector<std::set<std::thread::id>> idsOf(static_cast<std::size_t>(threads));
    pool.ParallelForOnThreads(2000, 3, [&](int thread, int begin, int end) {
      ASSERT_GE(thread, 0);
      ASSERT_LT(thread, threads);
      {
        const std::lock_guard lock(mutex);
        idsOf[static_cast<std::size_t>(thread)].insert(std::this_thread::get_id());
      }
      for (int i = begin; i < end; ++i) scratch[static_cast<std::size_t>(thread)].push_back(i);
    });
    std::vector<int> all;
    for (std::size_t t = 0; t < scratch.size(); ++t) {
      EXPECT_LE(idsOf[t].size(), 1u) << "thread number " << t << " ran on several threads";
      all.insert(all.end(), scratch[t].begin(), scratch[t].end());
    }
    EXPECT_EQ(idsOf[0].count(std::this_thread::get_id()), idsOf[0].size()) << "0 is the calling thread";
    std::sort(all.begin(), all.end());
    ASSERT_EQ(all.size(), 2000u);
    for (int i = 0; i < 2000; ++i) EXPECT_EQ(all[static_cast<std::size_t>(i)], i);
    const std::span<std::vector<int>> again = pool.ThreadScratch<std::vector<int>>();
    EXPECT_EQ(again.data(), scratch.data());
    EXPECT_EQ(pool.ThreadScratch<double>().size(), static_cast<std::size_t>(threads));
  }
}

// Thousands of small jobs back to back: the hand-off between jobs (late
// workers, counter resets) is where a race would show, here or under TSan.
TEST(JobPool, ManyShortJobsSumExactly) {
  JobPool pool(3);
  std::vector<long long> slots(97);
  long long expected = 0;
  for (int job = 0; job < 2000; ++job) {
    pool.ParallelFor(97, 5, [&slots, job](int begin, int end) {
      for (int i = begin; i < end; ++i) slots[static_cast<std::size_t>(i)] += job + i;
    });
    expected += job;
  }
  for (int i = 0; i < 97; ++i) EXPECT_EQ(slots[static_cast<std::size_t>(i)], expected + 2000LL * i);
}

// RunPhases: a chain of loops where each phase reads what the one before
// wrote at other items (a neighbour), so a chunk run before the earlier
// phase finished, or without seeing its writes, changes the answer (and
// ThreadSanitizer, which runs this suite, reports the missing ordering).
// Phase sizes include empty phases, a single-chunk phase and uneven ones.
TEST(JobPool, PhasesRunInOrderAndSeeTheEarlierPhasesWrites) {
  constexpr int kItems = 203;
  const std::vector<JobPhase> phases = {{kItems, 7},   {0, 4},      {kItems, 64}, {1, 1},      {kItems, 1},
                                        {kItems, 300}, {kItems, 5}, {0, 1},       {kItems, 13}};
  // Serial reference: phase p sets x_p[i] = x_{p-1}[i] + 3 x_{p-1}[(i + 1) % n]
  // (+ p), on ints (exact); phases of fewer items touch only their items.
  const auto run = [&](JobPool& pool) {
    std::vector<std::vector<long long>> x(phases.size() + 1, std::vector<long long>(kItems));
    for (int i = 0; i < kItems; ++i) x[0][static_cast<std::size_t>(i)] = i;
    std::vector<std::atomic<int>> visits(phases.size());
    pool.RunPhases(phases, [&](int p, int begin, int end) {
      const auto& in = x[static_cast<std::size_t>(p)];
      auto& out = x[static_cast<std::size_t>(p) + 1];
      // Items this phase does not cover carry over (the copy is the
      // chunk's own items when the phase covers all of them).
      for (int i = begin; i < end; ++i) {
        out[static_cast<std::size_t>(i)] =
            in[static_cast<std::size_t>(i)] + 3 * in[static_cast<std::size_t>((i + 1) % kItems)] + p;
      }
      visits[static_cast<std::size_t>(p)].fetch_add(end - begin);
    });
    for (std::size_t p = 0; p < phases.size(); ++p) {
      EXPECT_EQ(visits[p].load(), std::max(phases[p].count, 0)) << "phase " << p;
    }
    return x;
  };
  // Phases with fewer items than kItems leave the rest of their output at
  // zero, in every run alike; the reference is the one-thread pool.
  JobPool one(1);
  const auto reference = run(one);
  EXPECT_NE(reference.back()[0], 0);
  for (const int threads : {2, 3, 8}) {
    JobPool pool(threads);
    for (int repeat = 0; repeat < 50; ++repeat) {
      ASSERT_EQ(run(pool), reference) << threads << " threads, repeat " << repeat;
    }
  }
}

TEST(JobPool, PhasesWithNothingToDoCallNothing) {
  JobPool pool(3);
  int calls = 0;
  pool.RunPhases({}, [&](int, int, int) { ++calls; });
  const std::vector<JobPhase> empty = {{0, 1}, {-2, 4}};
  pool.RunPhases(empty, [&](int, int, int) { ++calls; });
  EXPECT_EQ(calls, 0);
}

TEST(JobPool, PoolsStartAndStopWithoutWork) {
  for (int i = 0; i < 20; ++i) {
    JobPool pool(1 + i % 8);
    EXPECT_EQ(pool.ThreadCount(), 1 + i % 8);
  }
}

}  // namespace job_pool_test
}  // namespace talus
