// The accuracy gate: a backend's metrics against the tolerances written in
// the scenario files. A checked metric that fails, a run the backend
// refused, or no result at all for the backend is a problem; each problem
// is one readable line naming the run, the metric and by how much it
// missed, e.g.
//   box_slide[mu=0.3,v0=1] sliding_stop.distance: measured 0.1811 m,
//   expected 0.1688 m (+- 0.00507), off by 0.0123 m, 0.00723 m beyond the tolerance
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "talus/harness/run/results_file.h"

namespace talus::harness {

struct CheckOutcome {
  int runs = 0;                       ///< results of the backend looked at
  int checkedMetrics = 0;             ///< metrics with a tolerance, gated for the backend
  int failedMetrics = 0;              ///< of those, failing
  std::vector<std::string> problems;  ///< one line each, in results order
  /// Judged metrics outside the gate for this backend (a truth's "ungated"
  /// entry or gate false), one line each with the verdict and the reason, so
  /// a known failure stays in sight.
  std::vector<std::string> ungated;
  /// Whether nothing regressed.
  [[nodiscard]] bool Ok() const { return problems.empty(); }
};

/// Checks every result of `backend` in `file`.
CheckOutcome CheckResults(const ResultsFile& file, std::string_view backend);

/// The backends `talus-testbed check` gates when none is named: every
/// Talus variant among `registered` (the name `talus` or `talus-...`), in
/// registry order.
std::vector<std::string> TalusVariants(const std::vector<std::string>& registered);

}  // namespace talus::harness
