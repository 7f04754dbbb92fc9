// The report's text outputs: the overview table, summary.md and
// results.csv (report.h), plus the number formatting they share.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "report/report_html_replay.h"
#include "report/report_peers.h"
#include "report/report_scorecard.h"
#include "support/text_util.h"
#include "talus/harness/report/bench_summary.h"
#include "talus/harness/report/report.h"
#include "talus/harness/sweep/sweep.h"

namespace talus::harness {

namespace {

// Results grouped by run id, in first-appearance order; within a run, by backend.
struct RunGroup {
  std::string runId;
  std::map<std::string, const RunResult*> byBackend;
};

std::vector<RunGroup> GroupByRun(const ResultsFile& file) {
  std::vector<RunGroup> groups;
  for (const RunResult& r : file.results) {
    if (groups.empty() || groups.back().runId != r.runId) groups.push_back({r.runId, {}});
    groups.back().byBackend[r.backend] = &r;
  }
  return groups;
}

// "+0.0012 ok" / "+0.0012 FAIL" / "+0.0012" (no tolerance) / "error"; with
// an anchor, a FAIL links to it: "+0.0012 [FAIL](#anchor)".
std::string Cell(const RunResult* r, const std::string& metric, const std::string& anchor = "") {
  if (r == nullptr) return "-";
  if (!r->error.empty()) return "error";
  const MetricResult* m = FindMetric(*r, metric);
  if (m == nullptr) return "-";
  std::string_view sign = std::isnan(m->measured) || m->error < 0.0 ? "" : "+";
  const std::string value = std::isnan(m->measured) ? std::string("not measured") : FormatNumber(m->error, 3);
  // A truth ungated for this backend is still judged and shown so.
  const auto fail = [&](std::string_view word) {
    return anchor.empty() ? Concat({" ", word}) : Concat({" [", word, "](#", anchor, ")"});
  };
  if (!m->ungated.empty()) return Concat({sign, value, m->pass ? " ok (ungated)" : fail("FAIL (ungated)")});
  std::string mark = !m->checked ? "" : m->pass ? " ok" : fail("FAIL");
  return Concat({sign, value, mark});
}

std::string Microseconds(double seconds) { return FormatNumber(seconds * 1e6, 3); }

// The reference a metric's error is measured from, as text.
std::string Expected(const MetricResult& m) {
  std::string text = FormatNumber(m.truth);
  if (!std::isnan(m.truthIntegrator))
    text.append(" (integrator ").append(FormatNumber(m.truthIntegrator)).append(")");
  // A published figure for the same case sits beside the truth, so the
  // reader compares the measured values with it.
  if (!std::isnan(m.publishedValue)) {
    text.append("; published ").append(FormatNumber(m.publishedValue));
    if (!std::isnan(m.publishedUpper)) text.append(" to ").append(FormatNumber(m.publishedUpper));
    text.append(" (").append(m.publishedSource).append(")");
  }
  return text;
}

std::string ToleranceText(const MetricResult& m) {
  if (!m.checked && m.ungated.empty()) return "-";
  std::string text;
  if (m.tolerance.absolute > 0.0) text.append(FormatNumber(m.tolerance.absolute)).append(" ").append(m.unit);
  if (m.tolerance.relative > 0.0) {
    if (!text.empty()) text.append(" + ");
    text.append(FormatNumber(100.0 * m.tolerance.relative)).append("%");
  }
  return text;
}

void Row(std::ostringstream& out, const std::vector<std::string>& cells) {
  out << "|";
  for (const std::string& cell : cells) out << " " << cell << " |";
  out << "\n";
}

void Header(std::ostringstream& out, const std::vector<std::string>& cells) {
  Row(out, cells);
  out << "|";
  for (std::size_t i = 0; i < cells.size(); ++i) out << "---|";
  out << "\n";
}

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted.push_back('"');
    quoted.push_back(c);
  }
  quoted.push_back('"');
  return quoted;
}

std::string CsvNumber(double value) {
  if (std::isnan(value)) return "";
  return FormatNumber(value, 17);
}

}  // namespace

std::string OverviewTable(const ResultsFile& file, bool linkFails) {
  std::ostringstream out;
  std::vector<std::string> header = {"run", "metric", "truth"};
  for (const std::string& b : file.backends) header.push_back(b);
  Header(out, header);
  // Cost is what a user waits for: each backend's total wall time over the
  // runs that every backend of the table finished (a run one of them
  // failed would make the sums unlike).
  std::map<std::string, double> totals;
  int finishedByAll = 0;
  const std::map<std::string, std::string> anchors = RunAnchors(file);
  for (const RunGroup& group : GroupByRun(file)) {
    // The checked metrics of the run, named by whichever backend has them.
    std::vector<const MetricResult*> metrics;
    std::set<std::string> seen;
    for (const std::string& b : file.backends) {
      const auto it = group.byBackend.find(b);
      if (it == group.byBackend.end()) continue;
      for (const MetricResult& m : it->second->metrics) {
        if (m.checked && seen.insert(m.name).second) metrics.push_back(&m);
      }
    }
    const bool allFinished =
        std::all_of(file.backends.begin(), file.backends.end(), [&](const std::string& b) {
          const auto it = group.byBackend.find(b);
          return it != group.byBackend.end() && it->second->error.empty();
        });
    if (allFinished) {
      ++finishedByAll;
      for (const std::string& b : file.backends) totals[b] += group.byBackend.at(b)->wallSeconds;
    }
    for (const MetricResult* m : metrics) {
      std::vector<std::string> row = {
          group.runId, Concat({m->name, m->unit.empty() ? "" : " (", m->unit, m->unit.empty() ? "" : ")"}),
          Expected(*m)};
      for (const std::string& b : file.backends) {
        const auto it = group.byBackend.find(b);
        row.push_back(Cell(it == group.byBackend.end() ? nullptr : it->second, m->name,
                           linkFails ? anchors.at(group.runId) : ""));
      }
      Row(out, row);
    }
  }
  // No run finished by every backend (each run's scenario lists its own
  // backends, or each run failed somewhere): nothing to sum, so no row of
  // dashes.
  if (finishedByAll == 0) return out.str();
  std::vector<std::string> timeRow = {
      Concat({"the ", std::to_string(finishedByAll), " runs every backend finished"}), "total wall time (s)",
      "-"};
  for (const std::string& b : file.backends) timeRow.push_back(FormatNumber(totals[b], 3));
  Row(out, timeRow);
  return out.str();
}

std::string SummaryTitle(const ResultsFile& file) {
  std::ostringstream out;
  out << "# Talus testbed report\n\n";
  out << "Backends: " <<
      [&] {
        std::string list;
        for (const std::string& b : file.backends) list.append(list.empty() ? "" : ", ").append(b);
        return list;
      }()
      << ". Errors are measured minus the truth (minus the integrator-exact answer where one exists); "
         "ok/FAIL compares them with the scenario file's tolerance"
      << (file.deterministic ? "; wall times are zeroed (deterministic mode)" : "") << ".\n\n";
  return out.str();
}

namespace {

// A run's heading and the line that says what it ran.
void RunHeading(std::ostringstream& out, const RunGroup& group) {
  out << "## " << group.runId << "\n\n";
  const RunResult& first = *group.byBackend.begin()->second;
  out << "Scenario `" << first.scenario << "` (" << first.file << "), time step "
      << FormatNumber(first.timeStep) << " s, " << first.steps << " steps, iterations "
      << (first.iterations > 0 ? std::to_string(first.iterations) : std::string("engine default")) << ".\n\n";
}

// Every metric any backend reported for the run, each once, in the order
// first met.
std::vector<const MetricResult*> RunMetrics(const RunGroup& group) {
  std::vector<const MetricResult*> metrics;
  std::set<std::string> seen;
  for (const auto& [backend, result] : group.byBackend) {
    for (const MetricResult& m : result->metrics) {
      if (seen.insert(m.name).second) metrics.push_back(&m);
    }
  }
  return metrics;
}

// The run's table: a row per metric, a column per backend, then the wall
// times.
void RunTable(std::ostringstream& out, const std::vector<std::string>& backends, const RunGroup& group,
              const std::vector<const MetricResult*>& metrics) {
  std::vector<std::string> header = {"metric", "truth", "tolerance"};
  for (const std::string& b : backends) header.push_back(b);
  Header(out, header);
  for (const MetricResult* m : metrics) {
    std::vector<std::string> row = {
        Concat({m->name, m->unit.empty() ? "" : " (", m->unit, m->unit.empty() ? "" : ")"}), Expected(*m),
        ToleranceText(*m)};
    for (const std::string& b : backends) {
      const auto it = group.byBackend.find(b);
      const RunResult* r = it == group.byBackend.end() ? nullptr : it->second;
      const MetricResult* own = r == nullptr ? nullptr : FindMetric(*r, m->name);
      // Measured values for unchecked metrics (drift, penetration); errors for truths.
      if (own != nullptr && !own->checked && own->ungated.empty() && r->error.empty()) {
        row.push_back(FormatNumber(own->measured, 3));
      } else {
        row.push_back(Cell(r, m->name));
      }
    }
    Row(out, row);
  }
  std::vector<std::string> time = {"wall time, total (ms) / longest step (us)", "-", "-"};
  for (const std::string& b : backends) {
    const auto it = group.byBackend.find(b);
    if (it == group.byBackend.end() || !it->second->error.empty()) {
      time.push_back(it == group.byBackend.end() ? "-" : "error");
      continue;
    }
    time.push_back(Concat({FormatNumber(it->second->wallSeconds * 1e3, 3), " / ",
                           Microseconds(it->second->wallSecondsLongestStep)}));
  }
  Row(out, time);
}

// The lines under a run's table: who stopped it, the broad phase that ran,
// why each tolerance has its size, why a backend is outside the gate, and
// each FAIL's cause.
void RunNotes(std::ostringstream& out, const std::vector<std::string>& backends, const RunGroup& group,
              const std::vector<const MetricResult*>& metrics) {
  for (const auto& [backend, result] : group.byBackend) {
    if (!result->error.empty()) out << "\n" << backend << " stopped the run: " << result->error << "\n";
  }
  // The broad-phase structure that met the pairs (figure 2), where the
  // run was replayed with the engine's step counters.
  for (const auto& [backend, result] : group.byBackend) {
    const std::string ran = StructureThatRan(result->replay);
    if (!ran.empty()) out << "\n" << backend << " broad phase: " << ran << "\n";
  }
  std::set<std::string> notes;
  for (const MetricResult* m : metrics) {
    if (!m->reason.empty() && notes.insert(m->reason).second) out << "\nTolerance: " << m->reason << "\n";
  }
  for (const auto& [backend, result] : group.byBackend) {
    // One line per reason: FAILS when any of its metrics fails.
    std::map<std::string, bool> failsByReason;
    for (const MetricResult& m : result->metrics) {
      if (!m.ungated.empty()) failsByReason[m.ungated] = failsByReason[m.ungated] || !m.pass;
    }
    for (const auto& [reason, fails] : failsByReason) {
      out << "\n"
          << backend << " is not gated on this truth (" << (fails ? "FAILS" : "passes") << "): " << reason
          << "\n";
    }
  }
  // Each FAIL's cause: a setting when the "-tuned" configuration removes it.
  const std::string causes = FailCauseLines(backends, group.byBackend);
  if (!causes.empty()) out << "\nFAILs and their cause:\n\n" << causes;
}

// Each backend's settings as recorded for the first run it built, its
// departures from the engine's defaults first.
void EngineSettings(std::ostringstream& out, const ResultsFile& file) {
  out << "## Engine settings\n\nAs recorded by each backend for the first run it built. For a peer, the "
         "settings that depart from what the engine gives a new user come first, each with why and its "
         "measured effect (`defaults` configurations change only what the scenario needs to be posed; "
         "`-tuned` ones follow the engine's documented practice).\n\n";
  for (const std::string& b : file.backends) {
    const auto it = std::find_if(file.results.begin(), file.results.end(),
                                 [&](const RunResult& r) { return r.backend == b && r.error.empty(); });
    out << "### " << b << "\n\n";
    if (it == file.results.end()) {
      out << "No run was built.\n\n";
      continue;
    }
    const std::string departures = DeparturesTable(it->settings);
    if (!departures.empty())
      out << "Departures from the engine's defaults:\n\n" << departures << "\nAll settings:\n\n";
    Header(out, {"setting", "value"});
    for (const Setting& s : it->settings) Row(out, {s.key, s.value});
    out << "\n";
  }
}

}  // namespace

std::string SummaryRuns(const ResultsFile& file) {
  std::ostringstream out;
  out << "## Overview\n\n" << OverviewTable(file, true) << "\n";
  for (const RunGroup& group : GroupByRun(file)) {
    RunHeading(out, group);
    const std::vector<const MetricResult*> metrics = RunMetrics(group);
    RunTable(out, file.backends, group, metrics);
    RunNotes(out, file.backends, group, metrics);
    out << "\n";
  }
  EngineSettings(out, file);
  return out.str();
}

std::string SummaryMarkdown(const ResultsFile& file, const ReportExtras& extras) {
  std::ostringstream out;
  out << SummaryTitle(file) << ScorecardMarkdown(BuildScorecard(file, extras)) << SummaryRuns(file);
  if (extras.satCheck != nullptr) out << SatCheckMarkdown(*extras.satCheck);
  if (extras.sweep != nullptr) out << SweepMarkdown(AnalyseSweep(*extras.sweep, kSweepSingleSetting)) << "\n";
  if (extras.stress != nullptr) out << StressMarkdown(*extras.stress) << "\n";
  if (extras.scenes != nullptr) out << BenchMarkdown(*extras.scenes);
  return out.str();
}

std::string ResultsCsv(const ResultsFile& file) {
  std::ostringstream out;
  out << "scenario,run,backend,time_step_s,iterations,steps,wall_s_per_step_median,wall_s_per_step_mean,"
         "metric,unit,measured,truth,truth_integrator,error,tolerance_absolute,tolerance_relative,checked,"
         "pass,"
         "run_error\n";
  for (const RunResult& r : file.results) {
    const std::string prefix =
        Concat({CsvField(r.scenario), ",", CsvField(r.runId), ",", CsvField(r.backend), ",",
                CsvNumber(r.timeStep), ",", std::to_string(r.iterations), ",", std::to_string(r.steps), ",",
                CsvNumber(r.wallSecondsPerStepMedian), ",", CsvNumber(r.wallSecondsPerStepMean), ","});
    if (r.metrics.empty()) out << prefix << ",,,,,,,,,," << CsvField(r.error) << "\n";
    for (const MetricResult& m : r.metrics) {
      out << prefix << CsvField(m.name) << "," << CsvField(m.unit) << "," << CsvNumber(m.measured) << ","
          << CsvNumber(m.truth) << "," << CsvNumber(m.truthIntegrator) << "," << CsvNumber(m.error) << ","
          << CsvNumber(m.tolerance.absolute) << "," << CsvNumber(m.tolerance.relative) << ","
          << (m.checked ? "true" : "false") << "," << (m.pass ? "true" : "false") << "," << CsvField(r.error)
          << "\n";
    }
  }
  return out.str();
}

}  // namespace talus::harness
