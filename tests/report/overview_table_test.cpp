// The overview table's cost row (OverviewTable, report_text.cpp): each
// backend's total wall time over the runs every backend finished. When no
// run was finished by all of them, as when the only scenario lists its own
// backends ("backends": ["talus"]) and more were asked for, there is
// nothing to sum: the row is left out, not printed as a row of "-"
// (issue 39).
#include <gtest/gtest.h>

#include <string>

#include "support/synthetic_results.h"
#include "talus/harness/report/report.h"
#include "talus/harness/run/results_file.h"

namespace talus::harness {
namespace overview_table_test {

RunResult Timed(const std::string& runId, const std::string& backend, double wallSeconds) {
  RunResult r =
      testing_support::SyntheticRun(runId, backend, {testing_support::SyntheticTruth("a", 0.0)}, 1e-5);
  r.wallSeconds = wallSeconds;
  return r;
}

TEST(OverviewTable, NoCostRowWhenNoRunRanOnEveryBackend) {
  ResultsFile file;
  file.backends = {"talus", "bullet"};
  file.results.push_back(Timed("own_backends", "talus", 0.5));  // its scenario lists talus alone
  const std::string table = OverviewTable(file);
  EXPECT_NE(table.find("| own_backends | a (m) |"), std::string::npos) << table;
  EXPECT_EQ(table.find("total wall time"), std::string::npos) << table;
  EXPECT_EQ(table.find("| - | - |\n"), std::string::npos) << table;
}

TEST(OverviewTable, CostRowSumsTheRunsEveryBackendFinished) {
  ResultsFile file;
  file.backends = {"talus", "bullet"};
  file.results.push_back(Timed("own_backends", "talus", 0.5));
  file.results.push_back(Timed("both", "talus", 0.25));
  file.results.push_back(Timed("both", "bullet", 2.0));
  const std::string table = OverviewTable(file);
  EXPECT_NE(table.find("| the 1 runs every backend finished | total wall time (s) | - | 0.25 | 2 |"),
            std::string::npos)
      << table;
}

}  // namespace overview_table_test
}  // namespace talus::harness
