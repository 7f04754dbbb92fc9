// The max_speed truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/max_speed.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// No listed body moves faster than the tolerance (m/s, absolute) over the
/// window [from, until] (seconds): the metric is the largest centre-of-mass
/// speed at the recorded samples in the window. A push-out that throws
/// overlapping bodies apart, or a pile that has not come to rest by the end,
/// fails it.
struct MaxSpeedTruth {
  static constexpr std::string_view kName = "max_speed";
  std::vector<int> bodies;  ///< body indices (dynamic), file order; default every dynamic body
  double from = 0.0;        ///< seconds, window start, >= 0
  double until = 0.0;       ///< seconds, window end, in (from, the run's end]
  bool operator==(const MaxSpeedTruth&) const = default;

  static std::string_view Schema();
  static Result<MaxSpeedTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth, const MaxSpeedTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
