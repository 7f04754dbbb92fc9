// The accuracy gate: a backend's metrics against the tolerances written in
// the scenario files of this checkout. Nothing the results file says about
// its own verdicts is trusted: every tolerance and whether it is gated is
// re-derived from the scenarios, every verdict recomputed from the
// measured value, and a file that does not hold exactly the checkout's
// runs, each with the checkout's tolerances, is refused with the
// difference named. A checked metric that fails, or a run the backend
// refused, is a problem; each problem is one readable line naming the run,
// the metric and by how much it missed, e.g.
//   box_slide[mu=0.3,v0=1] sliding_stop.distance: measured 0.1811 m,
//   expected 0.1688 m (+- 0.00507), off by 0.0123 m, 0.00723 m beyond the tolerance
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "talus/harness/backend/backend.h"
#include "talus/harness/run/results_file.h"
#include "talus/harness/run/runner.h"
#include "talus/result.h"

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

/// How the checkout judges one metric of a run's truths: its name, the
/// tolerance the scenario gives it (secondary bounds and step allowances
/// included) and whether it counts in the gate for the backend.
struct ExpectedMetric {
  std::string name;
  Tolerance tolerance;
  bool checked = false;  ///< has a tolerance and is gated for the backend
  std::string ungated;   ///< why it is outside the gate for the backend, else empty
};

/// The metrics the runner writes for `run`'s truths on `backend`, in its
/// order, with their tolerances and gating, derived by the truths' own
/// evaluators (truth_check.h) on a stand-in trajectory of the run's step,
/// sampling (RunnerOptions{}.maxSamples) and initial state: everything but
/// the measured numbers.
std::vector<ExpectedMetric> ExpectedMetrics(const Run& run, std::string_view backend);

/// The verdict of a measured metric against `tolerance`, recomputed:
/// |measured - reference| <= absolute + relative |truth|, the reference
/// being the integrator's answer where the truth has one; a threshold test
/// for a tipping truth (incline_tip.tilt.tips: tilt above the bound;
/// stays and slides: below). NaN anywhere fails.
bool RecomputedPass(const MetricResult& metric, const Tolerance& tolerance);

/// Checks every result of every backend in `backends` against `runs` (the
/// checkout's scenarios, loaded): one outcome per backend, in that order.
/// An Error, naming each difference (at most 20 lines), when the file is
/// not the checkout's: a run of the file that the checkout does not have
/// or that has other steps or another time step; a run of the checkout
/// (on a backend its scenario runs on, per `registry`) missing from the
/// file; a run whose scenario has no truth (nothing to gate); metrics other
/// than the checkout's, or a tolerance that differs from the one re-derived
/// from the scenario.
Result<std::vector<CheckOutcome>> RecheckResults(const ResultsFile& file, const std::vector<Run>& runs,
                                                 const std::vector<std::string>& backends,
                                                 const BackendRegistry& registry);

/// A Talus variant that `talus-testbed check` leaves out unless it is named
/// with --backend, and why. The report still judges and shows its every
/// truth (its FAILs are results); only the CI gate passes over it.
struct UngatedVariant {
  std::string_view name;
  std::string_view reason;
};

/// The Talus variants outside the default gate (docs/testbed-runner.md).
std::span<const UngatedVariant> UngatedTalusVariants();

/// The backends `talus-testbed check` gates when none is named: every
/// Talus variant among `registered` (the name `talus` or `talus-...`), in
/// registry order, but those of UngatedTalusVariants.
std::vector<std::string> TalusVariants(const std::vector<std::string>& registered);

}  // namespace talus::harness
