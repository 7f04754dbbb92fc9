// The momentum_conserved truth kind's fields (the table: truth_kinds.h). Its
// schema fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/momentum_conserved.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// The linear momentum of the listed bodies (every dynamic body when none
/// are listed), sum m v, stays at its start: the metric is the largest
/// |P(t) - P(0)| over the recorded samples, in kg m/s, judged against the
/// tolerance (absolute). Only without gravity and static bodies (the
/// loader refuses either): collisions among the bodies exchange momentum
/// but cannot change the total.
struct MomentumConservedTruth {
  static constexpr std::string_view kName = "momentum_conserved";
  std::vector<int> bodies;  ///< body indices (dynamic), file order
  bool operator==(const MomentumConservedTruth&) const = default;

  static std::string_view Schema();
  static Result<MomentumConservedTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth,
                                            const MomentumConservedTruth& kind, const Trajectory& trajectory);
};

}  // namespace talus::harness
