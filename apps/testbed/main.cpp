// talus-testbed: the command line of the testbed. Parses arguments with
// CLI11 and hands them to the subcommands (testbed_commands.h).
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <limits>
#include <string>

#include "sweep_commands.h"
#include "talus/harness/run/runner.h"
#include "talus/harness/scenario/scenario_limits.h"
#include "talus/harness/support/number_text.h"
#include "talus/world_settings.h"
#include "testbed_commands.h"
#include "testbed_flags.h"
#include "unknown_subcommand.h"

namespace {

using namespace talus::testbed;

// A number that is 0 (none) or in [low, high]: anything else, NaN
// included, is refused naming the value and the range (CLI11 adds the flag).
CLI::Validator ZeroOrWithin(double low, double high, const std::string& unit) {
  const std::string range = "0 (none) or " + talus::harness::FormatNumber(low, 17) + " to " +
                            talus::harness::FormatNumber(high, 17);
  return CLI::Validator(
      [=](const std::string& text) -> std::string {
        double value = 0.0;
        std::size_t used = 0;
        try {
          value = std::stod(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used != text.size() || !(value == 0.0 || (value >= low && value <= high))) {
          return text + " is not " + range + " " + unit;
        }
        return {};
      },
      "0|" + talus::harness::FormatNumber(low, 17) + ".." + talus::harness::FormatNumber(high, 17));
}

// `run`: scenarios through backends into results.json.
CLI::App* AddRunCommand(CLI::App& app, RunOptions& run) {
  CLI::App* command = app.add_subcommand("run", "run scenarios through backends and write results.json");
  command->add_option("scenarios", run.scenarios, "scenario files or folders (default: scenarios/)");
  command->add_option("-b,--backend", run.backends, "backends to run (repeat or comma-separate)")
      ->delimiter(',');
  command
      ->add_option("--time-step", run.timeSteps, "run each scenario at these time steps (s, comma-separated)")
      ->delimiter(',')
      ->check(kTimeStepRange);
  command
      ->add_option("--iterations", run.iterations,
                   "run each scenario with these solver iterations (0 = default)")
      ->delimiter(',')
      ->check(kIterationsRange);
  command->add_option("-o,--out", run.out, "output folder for results.json")->capture_default_str();
  command->add_option("-j,--jobs", run.jobs, "threads (0 = every core)")->check(kJobsRange);
  command
      ->add_option("--threads", run.threads,
                   "threads inside each Talus world (WorldSettings::threads; results are bit-identical, "
                   "only wall time changes)")
      ->check(InRange(1, talus::kMaxThreads));
  command
      ->add_option("--budget", run.budget,
                   "wall-clock seconds per job; a job past it stops with the reason, one stuck inside a step "
                   "is killed 2 s later (0 = no budget)")
      ->check(ZeroOrWithin(0.0, talus::harness::kMaxBudgetSeconds, "s"))
      ->capture_default_str();
  CLI::Option* memoryLimit =
      command
          ->add_option(
              "--memory-limit", run.memoryLimitMiB,
              "address space each job's process may add, MiB; past it the job stops naming the limit "
              "(0 = none)")
          ->check(ZeroOrWithin(static_cast<double>(talus::harness::kMinMemoryLimitBytes >> 20),
                               static_cast<double>(talus::harness::kMaxMemoryLimitBytes >> 20), "MiB"))
          ->capture_default_str();
  command->add_flag("--deterministic", run.deterministic, "zero wall times so reruns are byte-identical");
  command->add_flag("-q,--quiet", run.quiet, "no progress on stderr");
  command
      ->add_option("--replay", run.replay,
                   "record poses, contacts and step counters of these runs for the 3D replay "
                   "(run ids, scenario names or all; comma-separated)")
      ->delimiter(',');
  command->add_flag("--full-trajectories", run.fullTrajectories,
                    "write results.trajectories.json exact, not thinned and rounded for display "
                    "(metrics are computed from the full trajectories either way)");
  command
      ->add_flag("--in-process", run.inProcess,
                 "run the jobs on threads of this process, not a child process each, for a debugger: a crash "
                 "then stops every job, and the budget stops a job only between steps (no memory limit)")
      ->excludes(memoryLimit);
  return command;
}

// `report`: summary.md, results.csv and report.html from a results.json.
CLI::App* AddReportCommand(CLI::App& app, ReportOptions& report) {
  CLI::App* command = app.add_subcommand("report", "write summary.md, results.csv and report.html");
  command->add_option("results", report.results, "results.json of a run")->required();
  command->add_option("-o,--out", report.out, "report folder (default: beside the results)");
  command->add_option("--chart-js", report.chartJs,
                      "charting library to inline (default: Chart.js from npm)");
  command->add_option("--three-js", report.threeJs, "3D library to inline (default: three.js from npm)");
  command->add_option("--sat-check", report.satCheck,
                      "talus-sat-check --json results to add as the SAT validation section");
  command->add_option("--sweep", report.sweep,
                      "results.json of `talus-testbed sweep` to add as the run-time-against-error section");
  command->add_option("--stress", report.stress,
                      "stress.json of `talus-testbed stress` to add as the stability envelope section");
  command->add_option("--scenes", report.scenes,
                      "`talus-scenes --format jsonl` output to add as the large-scenes section");
  return command;
}

// `check`: every Talus variant's metrics against the scenario tolerances.
CLI::App* AddCheckCommand(CLI::App& app, CheckOptions& check) {
  CLI::App* command =
      app.add_subcommand("check", "check every Talus variant's metrics against the scenario tolerances");
  command->add_option("scenarios", check.scenarios,
                      "scenario files or folders the verdicts are re-derived from (default: scenarios/)");
  command->add_option(
      "-r,--results", check.results,
      "check this results.json instead of running (it must hold exactly the scenarios' runs)");
  command
      ->add_option(
          "-b,--backend", check.backends,
          "backends whose metrics are checked (repeat or comma-separate; default: every Talus variant)")
      ->delimiter(',');
  command->add_option("-j,--jobs", check.jobs, "threads (0 = every core)")->check(kJobsRange);
  command->add_flag("-q,--quiet", check.quiet, "no progress on stderr");
  command->add_flag("--in-process", check.inProcess,
                    "run the jobs on threads of this process, not a child process each (for a debugger)");
  return command;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace talus::testbed;
  CLI::App app{"Talus testbed: runs scenarios through Talus, Bullet and ODE, reports and checks accuracy"};
  app.require_subcommand(1);
  RunOptions run;
  CLI::App* runCommand = AddRunCommand(app, run);
  ReportOptions report;
  CLI::App* reportCommand = AddReportCommand(app, report);
  CheckOptions check;
  AddCheckCommand(app, check);
  CommandAction chosen;
  AddSweepCommand(app, chosen);
  AddMergeCommand(app, chosen);
  AddStressCommand(app, chosen);

  // CLI11 would only say the word "was not expected": name it as a subcommand.
  if (const auto unknown = talus::cli::UnknownSubcommand(app, argc, argv)) {
    std::cerr << "talus-testbed: " << *unknown << "\n";
    return kExitBadInput;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? kExitOk : kExitBadInput;
  }
  int code = kExitOk;
  if (chosen) {
    code = chosen();
  } else if (*runCommand) {
    code = RunCommand(run);
  } else if (*reportCommand) {
    code = ReportCommand(report);
  } else {
    code = CheckCommand(check);
  }
  return FinishStdout(code);
}
