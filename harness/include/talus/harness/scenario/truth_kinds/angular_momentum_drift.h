// The angular_momentum_drift truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/angular_momentum_drift.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// Which angular momentum drift a truth measures.
enum class MomentumMetric {
  Vector,     ///< max |L(t) - L(0)| / |L(0)|: direction and magnitude
  Magnitude,  ///< max ||L(t)| - |L(0)|| / |L(0)|: magnitude only
};
/// A free body's angular momentum about its centre of mass (world frame,
/// L = I_world w) is conserved; the metric is its relative drift.
struct AngularMomentumDriftTruth {
  static constexpr std::string_view kName = "angular_momentum_drift";
  MomentumMetric metric = MomentumMetric::Vector;
  bool operator==(const AngularMomentumDriftTruth&) const = default;

  static std::string_view Schema();
  static Result<AngularMomentumDriftTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth,
                                            const AngularMomentumDriftTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
