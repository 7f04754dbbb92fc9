// The subcommands of talus-testbed: argument checks, loading, running,
// writing and printing. All numbers come from the harness library; this
// file only wires it to files and the terminal.
#include "testbed_commands.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <thread>

#include "sweep_commands.h"
#include "talus/harness/report/regression_check.h"
#include "talus/harness/report/report.h"
#include "talus/harness/run/results_file.h"
#include "talus/harness/run/runner.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/harness/scenes/bench_report_json.h"
#include "talus/harness/stress/stress.h"
#include "talus/reference/all_backends.h"

namespace talus::testbed {
namespace {

namespace fs = std::filesystem;
using harness::ResultsFile;

int Jobs(int asked) {
  if (asked > 0) return asked;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

std::vector<fs::path> ScenarioPaths(const std::vector<std::string>& given) {
  std::vector<fs::path> paths(given.begin(), given.end());
  if (paths.empty())
    paths.push_back(fs::exists("scenarios") ? fs::path("scenarios") : fs::path(TALUS_DEFAULT_SCENARIOS));
  return paths;
}

// Loads `run.scenarios` and runs them through `backends` (run.backends is
// not read: the caller has chosen the list); prints the error and returns
// nothing on bad input.
std::optional<ResultsFile> LoadAndRun(const RunOptions& run, const std::vector<std::string>& backends) {
  auto loaded = harness::LoadScenarios(ScenarioPaths(run.scenarios));
  if (!loaded) {
    std::cerr << "talus-testbed: " << loaded.GetError().message << "\n";
    return std::nullopt;
  }
  auto runs = harness::ExpandStepping(loaded.Value(), run.timeSteps, run.iterations);
  if (!runs) {
    std::cerr << "talus-testbed: " << runs.GetError().message << "\n";
    return std::nullopt;
  }
  harness::RunnerOptions options;
  options.backends = backends;
  options.jobs = Jobs(run.jobs);
  options.deterministic = run.deterministic;
  options.replay = run.replay;
  options.budgetSeconds = run.budget;
  options.memoryLimitBytes = run.inProcess ? 0 : run.memoryLimitMiB << 20;
  options.isolation = run.inProcess ? harness::JobIsolation::InProcess : harness::JobIsolation::Process;
  if (!run.quiet) options.progress = [](const std::string& line) { std::cerr << line << "\n"; };
  // Shown even with --quiet: a run that ran nowhere must not vanish unseen.
  options.notice = [](const std::string& line) { std::cout << "talus-testbed: " << line << "\n"; };
  // The shared registry unless the Talus worlds need another thread count.
  const std::optional<harness::BackendRegistry> threaded =
      run.threads == 1 ? std::nullopt : std::optional(reference::MakeAllBackends(run.threads));
  auto results = harness::RunAll(threaded ? *threaded : reference::AllBackends(), runs.Value(), options);
  if (!results) {
    std::cerr << "talus-testbed: " << results.GetError().message << "\n";
    return std::nullopt;
  }
  ResultsFile file;
  file.backends = backends;
  file.deterministic = run.deterministic;
  file.results = std::move(results).Value();
  return file;
}

// Prints every run a backend refused; whether there was one.
bool ReportRunErrors(const ResultsFile& file) {
  bool any = false;
  for (const harness::RunResult& r : file.results) {
    if (r.error.empty()) continue;
    std::cerr << "talus-testbed: " << r.runId << " with " << r.backend << " failed: " << r.error << "\n";
    any = true;
  }
  return any;
}

}  // namespace

std::vector<std::string> DefaultBackends() {
  // Every Talus variant (the coloured solver is shown so the testbed can
  // weigh it against the reference order); each peer in its defaults and
  // tuned configuration; Bullet's single-precision build where this build
  // has it (not under the sanitizers).
  std::vector<std::string> names = {"talus",    "talus-writeup",  "talus-split",   "talus-coloured",
                                    "bullet",   "bullet-tuned",   "bullet-f32",    "bullet-f32-tuned",
                                    "ode-step", "ode-step-tuned", "ode-quickstep", "ode-quickstep-tuned",
                                    "mujoco",   "mujoco-tuned"};
  std::erase_if(names, [](const std::string& name) { return !reference::AllBackends().Has(name); });
  return names;
}

int RunCommand(const RunOptions& options) {
  const std::vector<std::string> backends = options.backends.empty() ? DefaultBackends() : options.backends;
  auto file = LoadAndRun(options, backends);
  if (!file) return kExitBadInput;
  file->fullTrajectories = options.fullTrajectories;
  std::error_code error;
  fs::create_directories(options.out, error);
  if (error) {
    std::cerr << "talus-testbed: " << options.out << ": cannot make the output folder (" << error.message()
              << ")\n";
    return kExitBadInput;
  }
  const fs::path path = fs::path(options.out) / "results.json";
  auto written = harness::WriteResultsFile(path, *file);
  if (!written) {
    std::cerr << "talus-testbed: " << written.GetError().message << "\n";
    return kExitBadInput;
  }
  std::cout << harness::OverviewTable(*file) << "\nresults: " << path.string() << "\n";
  return ReportRunErrors(*file) ? kExitFailed : kExitOk;
}

// Reads the optional input at `path` with `read` into `out`; an empty path
// is no input. False (after printing the reader's message) when it fails.
template <typename T, typename Reader>
bool ReadExtra(const std::string& path, Reader read, std::optional<T>& out) {
  if (path.empty()) return true;
  auto value = read(path);
  if (!value) {
    std::cerr << "talus-testbed: " << value.GetError().message << "\n";
    return false;
  }
  out = std::move(value).Value();
  return true;
}

int ReportCommand(const ReportOptions& options) {
  auto file = harness::ReadResultsFile(options.results);
  if (!file) {
    std::cerr << "talus-testbed: " << file.GetError().message << "\n";
    return kExitBadInput;
  }
  if (const auto twice = harness::FindDuplicatedResult(file.Value().results)) {
    const harness::RunResult& result = file.Value().results[twice->second];
    std::cerr << "talus-testbed: " << options.results << ": run \"" << result.runId << "\" on backend \""
              << result.backend << "\" appears twice (results " << twice->first << " and " << twice->second
              << "); a results file holds each (run, backend) once\n";
    return kExitBadInput;
  }
  const fs::path folder =
      options.out.empty() ? fs::path(options.results).parent_path() : fs::path(options.out);
  const fs::path chartJs =
      options.chartJs.empty() ? fs::path(TALUS_DEFAULT_CHART_JS) : fs::path(options.chartJs);
  const fs::path threeJs =
      options.threeJs.empty() ? fs::path(TALUS_DEFAULT_THREE_JS) : fs::path(options.threeJs);
  // Each extra is read in full before anything is written, so a bad one
  // leaves the report folder untouched.
  std::optional<harness::SatCheckSummary> satCheck;
  std::optional<ResultsFile> sweep;
  std::optional<std::vector<harness::StressEntry>> stress;
  std::optional<std::vector<harness::BenchReport>> scenes;
  if (!ReadExtra(options.satCheck, harness::ReadSatCheckFile, satCheck) ||
      !ReadExtra(options.sweep, harness::ReadResultsFile, sweep) ||
      !ReadExtra(options.stress, harness::ReadStressFile, stress) ||
      !ReadExtra(options.scenes, harness::ReadBenchReportFile, scenes)) {
    return kExitBadInput;
  }
  const harness::ReportExtras extras{.satCheck = satCheck ? &*satCheck : nullptr,
                                     .sweep = sweep ? &*sweep : nullptr,
                                     .stress = stress ? &*stress : nullptr,
                                     .scenes = scenes ? &*scenes : nullptr};
  auto written =
      harness::WriteReport(file.Value(), folder.empty() ? fs::path(".") : folder, chartJs, threeJs, extras);
  if (!written) {
    std::cerr << "talus-testbed: " << written.GetError().message << "\n";
    return kExitBadInput;
  }
  const fs::path shown = folder.empty() ? fs::path(".") : folder;
  std::cout << harness::OverviewTable(file.Value()) << "\nreport: " << (shown / "report.html").string()
            << "\nsummary: " << (shown / "summary.md").string()
            << "\ndata: " << (shown / "results.csv").string() << ", " << (shown / "results.json").string()
            << "\n";
  return kExitOk;
}

int CheckCommand(const CheckOptions& options) {
  std::vector<std::string> backends = options.backends;
  // The checkout's scenarios (or those named): what every verdict is
  // re-derived from, whether the results are read or run here.
  auto runs = harness::LoadScenarios(ScenarioPaths(options.scenarios));
  if (!runs) {
    std::cerr << "talus-testbed: " << runs.GetError().message << "\n";
    return kExitBadInput;
  }
  ResultsFile file;
  if (!options.results.empty()) {
    auto read = harness::ReadResultsFile(options.results);
    if (!read) {
      std::cerr << "talus-testbed: " << read.GetError().message << "\n";
      return kExitBadInput;
    }
    file = std::move(read).Value();
    // By default every Talus variant the results (and so their report) show.
    if (backends.empty()) backends = harness::TalusVariants(file.backends);
  } else {
    // By default every registered Talus variant.
    if (backends.empty()) backends = harness::TalusVariants(reference::AllBackends().Names());
    // The check's own run: deterministic, and without the run command's
    // budget and memory limit (0 = none), as before they were options.
    RunOptions run;
    run.scenarios = options.scenarios;
    run.jobs = options.jobs;
    run.deterministic = true;
    run.quiet = options.quiet;
    run.budget = 0.0;
    run.memoryLimitMiB = 0;
    run.inProcess = options.inProcess;
    auto ran = LoadAndRun(run, backends);
    if (!ran) return kExitBadInput;
    file = std::move(*ran);
  }
  if (backends.empty()) {
    std::cerr << "talus-testbed: no Talus variant to check (name one with --backend)\n";
    return kExitBadInput;
  }
  if (options.backends.empty()) {
    for (const harness::UngatedVariant& variant : harness::UngatedTalusVariants()) {
      std::cout << "not gated: " << variant.name << ", " << variant.reason << "\n";
    }
  }
  auto outcomes = harness::RecheckResults(file, runs.Value(), backends, reference::AllBackends());
  if (!outcomes) {
    std::cerr << "talus-testbed: check refused " << (options.results.empty() ? "the run" : options.results)
              << ": " << outcomes.GetError().message << "\n";
    return kExitBadInput;
  }
  // Every backend is checked and reported, so one failing variant does not
  // hide another's verdict.
  bool ok = true;
  for (std::size_t b = 0; b < backends.size(); ++b) {
    const std::string& backend = backends[b];
    const harness::CheckOutcome& outcome = outcomes.Value()[b];
    if (!outcome.Ok()) {
      ok = false;
      std::cout << "check FAILED for " << backend << ": " << outcome.problems.size() << " problem(s)\n";
      for (const std::string& problem : outcome.problems) std::cout << "  " << problem << "\n";
    } else {
      std::cout << "check passed for " << backend << ": " << outcome.checkedMetrics << " metrics in "
                << outcome.runs << " runs within tolerance (verdicts recomputed from the scenarios)\n";
    }
    if (!outcome.ungated.empty()) {
      std::cout << "  " << outcome.ungated.size() << " metric(s) of " << backend << " outside the gate:\n";
      for (const std::string& line : outcome.ungated) std::cout << "    " << line << "\n";
    }
  }
  return ok ? kExitOk : kExitFailed;
}

int FinishStdout(int code) {
  // std::cout writes through stdio's stdout, so the flush shows a failure
  // of the last buffer. A write that failed earlier left cout bad and
  // stdio's error flag set, but its errno is long gone: one more byte
  // written straight to the descriptor (into an output that is already
  // incomplete) fails the same way and says why.
  std::cout.flush();
  errno = 0;
  const bool flushed = std::fflush(stdout) == 0;
  int error = errno;
  if (std::cout && flushed && std::ferror(stdout) == 0) return code;
  if (error == 0 && ::write(STDOUT_FILENO, "\n", 1) < 0) error = errno;
  std::cerr << "talus-testbed: stdout: cannot write (" << (error != 0 ? std::strerror(error) : "write failed")
            << ")\n";
  return code == kExitOk ? kExitBadInput : code;
}

}  // namespace talus::testbed
