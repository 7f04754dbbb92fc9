// What running every job in its own worker process costs (issue 26): the
// default suite on every registered backend, once with the jobs in worker
// processes (JobIsolation::Process, what `talus-testbed run` does) and once
// on this process's threads (JobIsolation::InProcess, no protection), at
// one job at a time so the two differ only by the isolation. Wall time is
// the cost a user waits for; the `cpu_s` counter adds the CPU time of this
// process and of every worker it waited for (getrusage of children), which
// a busy shared machine disturbs less. Results: docs/testbed-runner.md.
//
//   ./build/bench/talus_bench_runner_isolation --benchmark_repetitions=3
#include <sys/resource.h>

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <vector>

#include "talus/harness/run/runner.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/reference/all_backends.h"

namespace {

double CpuSeconds() {
  const auto seconds = [](int who) {
    rusage usage{};
    getrusage(who, &usage);
    return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  };
  return seconds(RUSAGE_SELF) + seconds(RUSAGE_CHILDREN);
}

const std::vector<talus::harness::Run>& DefaultSuite() {
  static const std::vector<talus::harness::Run> runs = [] {
    auto loaded = talus::harness::LoadScenarios({std::filesystem::path(TALUS_DEFAULT_SCENARIOS)});
    if (!loaded) {
      std::cerr << "runner_isolation: " << loaded.GetError().message << "\n";
      std::exit(2);
    }
    auto expanded = talus::harness::ExpandStepping(loaded.Value(), {}, {});
    if (!expanded) {
      std::cerr << "runner_isolation: " << expanded.GetError().message << "\n";
      std::exit(2);
    }
    return std::move(expanded).Value();
  }();
  return runs;
}

void BM_DefaultSuite(benchmark::State& state) {
  const auto& registry = talus::reference::AllBackends();
  talus::harness::RunnerOptions options;
  options.backends = registry.Names();
  options.jobs = 1;
  options.isolation =
      state.range(0) != 0 ? talus::harness::JobIsolation::Process : talus::harness::JobIsolation::InProcess;
  const std::vector<talus::harness::Run>& runs = DefaultSuite();
  double cpu = 0.0;
  for (auto _ : state) {
    const double before = CpuSeconds();
    auto results = talus::harness::RunAll(registry, runs, options);
    cpu += CpuSeconds() - before;
    if (!results) {
      state.SkipWithError(results.GetError().message.c_str());
      return;
    }
    benchmark::DoNotOptimize(results.Value().data());
  }
  state.counters["cpu_s"] = benchmark::Counter(cpu, benchmark::Counter::kAvgIterations);
  state.counters["runs"] = static_cast<double>(runs.size());
}

}  // namespace

// Arg 1: worker processes; 0: in-process threads. One iteration is one
// whole suite (tens of seconds); take medians over --benchmark_repetitions.
BENCHMARK(BM_DefaultSuite)->Arg(0)->Arg(1)->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);

BENCHMARK_MAIN();
