// Perturbed repeats of a reference scene (see talus/harness/scenes/bench_perturb.h).
#include "talus/harness/scenes/bench_perturb.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "support/numbers.h"
#include "talus/harness/support/number_text.h"

namespace talus::harness {

std::optional<std::string> BenchRepeatsProblem(int repeats) {
  if (repeats < 1 || repeats > kMaxBenchRepeats) {
    return "repeats " + std::to_string(repeats) + ": must be in [1, " + std::to_string(kMaxBenchRepeats) +
           "]";
  }
  return std::nullopt;
}

std::optional<double> BenchVerdictFigure(const BenchReport& report) {
  if (!report.skipped.empty()) return std::nullopt;
  return report.drift ? report.drift : report.maxPenetration;
}

std::optional<bool> BenchVerdict(const BenchReport& report) {
  if (!report.skipped.empty()) return std::nullopt;
  if (report.drift) return *report.drift <= kPyramidDriftGoal;  // false for NaN
  if (report.escaped) return *report.escaped == 0;
  return std::nullopt;
}

namespace {

// The median of a non-empty list.

}  // namespace

Result<BenchRepeatSummary> SummarizeRepeats(const std::vector<BenchReport>& repeats) {
  std::vector<double> figures;
  std::vector<double> totals;
  BenchRepeatSummary summary;
  bool anyNan = false;
  for (const BenchReport& report : repeats) {
    const std::optional<double> figure = BenchVerdictFigure(report);
    const std::optional<bool> verdict = BenchVerdict(report);
    if (!figure || !verdict) continue;
    anyNan = anyNan || std::isnan(*figure);
    figures.push_back(*figure);
    totals.push_back(report.totalMs);
    if (*verdict) ++summary.verdictsHeld;
  }
  if (figures.empty()) return Error{"no repeat was run (all skipped or empty), nothing to summarize"};
  summary.runs = static_cast<int>(figures.size());
  summary.sameVerdict = summary.verdictsHeld == 0 || summary.verdictsHeld == summary.runs;
  summary.totalMsMin = *std::min_element(totals.begin(), totals.end());
  summary.totalMsMax = *std::max_element(totals.begin(), totals.end());
  summary.totalMsMedian = Median(totals);
  if (anyNan) {
    summary.min = summary.median = summary.max = std::nan("");
    return summary;
  }
  summary.min = *std::min_element(figures.begin(), figures.end());
  summary.max = *std::max_element(figures.begin(), figures.end());
  summary.median = Median(figures);
  return summary;
}

std::string FormatRepeatSummary(const BenchReport& first, const BenchRepeatSummary& summary) {
  const bool pyramid = first.drift.has_value();
  std::ostringstream line;
  line << first.scene << " " << first.parameter << " " << first.engine << ": "
       << (pyramid ? "drift_m" : "max_penetration_m") << " over " << summary.runs << " repeats";
  if (first.perturbation) {
    line << " (+-" << FormatNumber(first.perturbation->amount) << " m, first seed "
         << first.perturbation->seed << ")";
  }
  line << ": min " << FormatNumber(summary.min) << " median " << FormatNumber(summary.median) << " max "
       << FormatNumber(summary.max) << "; verdict "
       << (pyramid ? "drift_m <= " + FormatNumber(kPyramidDriftGoal) : std::string("escaped == 0"))
       << " held in " << summary.verdictsHeld << " of " << summary.runs << ": "
       << (summary.sameVerdict ? "same in every repeat" : "DIFFERS between repeats") << "; total ms min "
       << FormatNumber(summary.totalMsMin) << " median " << FormatNumber(summary.totalMsMedian) << " max "
       << FormatNumber(summary.totalMsMax);
  return line.str();
}

}  // namespace talus::harness
