// The accuracy gate (regression_check.h): walks a backend's results and
// words every failure with the numbers a reader needs to judge it.
#include "talus/harness/report/regression_check.h"

#include <cmath>

#include "support/text_util.h"

namespace talus::harness {

CheckOutcome CheckResults(const ResultsFile& file, std::string_view backend) {
  CheckOutcome outcome;
  for (const RunResult& result : file.results) {
    if (result.backend != backend) continue;
    ++outcome.runs;
    if (!result.error.empty()) {
      outcome.problems.push_back(Concat({result.runId, ": the run failed: ", result.error}));
      continue;
    }
    for (const MetricResult& m : result.metrics) {
      if (!m.ungated.empty()) {
        outcome.ungated.push_back(
            Concat({result.runId, " ", m.name, ": ", m.pass ? "ok" : "FAIL", " (ungated: ", m.ungated, ")"}));
        continue;
      }
      if (!m.checked) continue;
      ++outcome.checkedMetrics;
      if (m.pass) continue;
      ++outcome.failedMetrics;
      const double allowed = m.tolerance.absolute + m.tolerance.relative * std::abs(m.truth);
      const double expected = std::isnan(m.truthIntegrator) ? m.truth : m.truthIntegrator;
      const std::string unit = m.unit.empty() ? "" : Concat({" ", m.unit});
      if (std::isnan(m.measured)) {
        outcome.problems.push_back(Concat(
            {result.runId, " ", m.name, ": not measured (expected ", FormatNumber(expected), unit, ")"}));
        continue;
      }
      outcome.problems.push_back(Concat(
          {result.runId, " ", m.name, ": measured ", FormatNumber(m.measured), unit, ", expected ",
           FormatNumber(expected), unit, " (+- ", FormatNumber(allowed), "), off by ", FormatNumber(m.error),
           unit, ", ", FormatNumber(std::abs(m.error) - allowed), unit, " beyond the tolerance"}));
    }
  }
  if (outcome.runs == 0) {
    outcome.problems.push_back(Concat({"no results for backend \"", backend, "\""}));
  }
  return outcome;
}

std::vector<std::string> TalusVariants(const std::vector<std::string>& registered) {
  std::vector<std::string> variants;
  for (const std::string& name : registered) {
    if (name == "talus" || name.rfind("talus-", 0) == 0) variants.push_back(name);
  }
  return variants;
}

}  // namespace talus::harness
