// Judging metrics and dispatching a truth to its kind's evaluator.
#include "talus/harness/truth/truth_check.h"

#include <cassert>
#include <cmath>
#include <type_traits>
#include <utility>

#include "truth/kinds/kind_support.h"

namespace talus::harness {

MetricResult MakeMetric(std::string name, std::string unit) {
  MetricResult metric;
  metric.name = std::move(name);
  metric.unit = std::move(unit);
  return metric;
}

void Judge(MetricResult& metric, const Tolerance& tolerance) {
  metric.tolerance = tolerance;
  metric.checked = tolerance.absolute > 0.0 || tolerance.relative > 0.0;
  const double reference = std::isnan(metric.truthIntegrator) ? metric.truth : metric.truthIntegrator;
  metric.error = metric.measured - reference;
  // A NaN measurement (nothing to measure) fails; NaN compares false.
  metric.pass = std::abs(metric.error) <= tolerance.absolute + tolerance.relative * std::abs(metric.truth);
}

std::string BoundReason(const Truth& truth, std::string_view field) {
  const auto found = truth.boundReasons.find(std::string(field));
  return found == truth.boundReasons.end() ? std::string() : found->second;
}

Vec3 UpAxis(const Run& run) {
  // Scaled by the largest component first: |g| of 1e300 would overflow to
  // inf and make the axis zero (every height 0), 1e-300 underflow to 0.
  const Vec3& gravity = run.scenario.world.gravity;
  const double scale = gravity.cwiseAbs().maxCoeff();
  return scale > 0.0 ? Vec3(-(gravity / scale).normalized()) : Vec3::UnitY();
}

std::vector<MetricResult> EvaluateTruth(const Run& run, const Truth& truth, const Trajectory& trajectory) {
  assert(!trajectory.samples.empty());
  // Each kind's own evaluator (its unit in src/truth/kinds/, the table
  // TruthKind); a converged reference returns nothing.
  std::vector<MetricResult> metrics = std::visit(
      [&](const auto& kind) {
        using Kind = std::decay_t<decltype(kind)>;
        return Kind::Evaluate(run, truth, kind, trajectory);
      },
      truth.kind);
  if (truth.published) {
    for (MetricResult& metric : metrics) {
      metric.publishedValue = truth.published->value;
      metric.publishedUpper = truth.published->upper;
      metric.publishedSource = truth.published->source;
    }
  }
  return metrics;
}

void ApplyGate(const Truth& truth, std::string_view backend, std::vector<MetricResult>& metrics) {
  // A metric judged against a secondary bound carries that bound's reason
  // (set by its evaluator); the others the tolerance's.
  for (MetricResult& metric : metrics) {
    if (metric.checked && metric.reason.empty()) metric.reason = truth.toleranceReason;
  }
  std::string reason;
  if (!truth.gate) reason = "gate false for every backend: " + truth.gateReason;
  for (const UngatedBackend& entry : truth.ungated) {
    if (entry.backend == backend) reason = entry.reason;
  }
  if (reason.empty()) return;
  // Judged and reported, but it never fails the check for this backend.
  for (MetricResult& metric : metrics) {
    if (!metric.checked) continue;
    metric.checked = false;
    metric.ungated = reason;
  }
}

}  // namespace talus::harness
