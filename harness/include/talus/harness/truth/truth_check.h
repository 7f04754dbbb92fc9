// Checking a run against its ground truths: one MetricResult per measured
// number (a free fall gives a height, a bounce series one apex per bounce).
//
// EvaluateTruth dispatches with std::visit over the table of truth kinds
// (TruthKind, scenario/truth_kinds.h) to each kind's evaluator, in its unit
// (harness/src/truth/kinds/<kind>.cpp). A converged reference has
// no closed form: the runner compares against a finer run of the same
// backend (runner.h), so EvaluateTruth returns nothing for it.
#pragma once

#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "talus/harness/backend/trajectory.h"
#include "talus/harness/scenario/scenario.h"

namespace talus::harness {

/// One measured number against its truth.
struct MetricResult {
  std::string name;       ///< stable identifier, e.g. "free_fall.height", "bounce_heights.apex2"
  std::string unit;       ///< "m", "m/s", "rad", "" (unitless)...
  double measured = 0.0;  ///< what the engine did (NaN when it could not be measured, e.g. no apex)
  double truth = 0.0;     ///< the continuous-time answer
  /// The exact answer of symplectic Euler at the run's step (truths.h);
  /// NaN when the kind defines none.
  double truthIntegrator = std::numeric_limits<double>::quiet_NaN();
  /// measured - reference, where the reference is truthIntegrator when it
  /// is defined (it removes the integrator error every engine shares at this
  /// step and leaves the solver's) and truth otherwise; NaN when measured is.
  double error = 0.0;
  Tolerance tolerance;  ///< from the scenario file
  std::string reason;   ///< the tolerance's physical reason (Truth::toleranceReason)
  /// Counted in the accuracy gate for this run's backend: the metric has a
  /// tolerance and its truth is not ungated for the backend (Truth::gate,
  /// Truth::ungated).
  bool checked = false;
  bool pass = false;  ///< |error| <= absolute + relative |truth| (judged even when not checked)
  /// Why a judged metric is outside the gate for this backend (the file's
  /// reason); empty when it is gated or is a reported-only quantity.
  std::string ungated;
  /// The truth's published figure (PublishedFigure), shown beside the
  /// measured value; NaN value when the truth has none.
  double publishedValue = std::numeric_limits<double>::quiet_NaN();
  double publishedUpper = std::numeric_limits<double>::quiet_NaN();
  std::string publishedSource;
};

/// A metric with its name and unit set and every number still unset.
MetricResult MakeMetric(std::string name, std::string unit);

/// Fills error, checked and pass of `metric` from measured, truth and `tolerance`.
void Judge(MetricResult& metric, const Tolerance& tolerance);

/// The metrics of `truth` measured on `trajectory` (a run of `run`); empty
/// for a converged reference. The trajectory must hold at least one sample.
std::vector<MetricResult> EvaluateTruth(const Run& run, const Truth& truth, const Trajectory& trajectory);

/// Gives the metrics `truth` produced on `backend` the tolerance's reason and
/// applies the truth's gate: when the truth is ungated (Truth::gate false, or
/// `backend` in Truth::ungated) each judged metric becomes unchecked and
/// carries the reason in `ungated`.
void ApplyGate(const Truth& truth, std::string_view backend, std::vector<MetricResult>& metrics);

/// The unit "up" direction of a run: -gravity normalised, or +y when there
/// is no gravity. Heights in truths are measured along it.
Vec3 UpAxis(const Run& run);

}  // namespace talus::harness
