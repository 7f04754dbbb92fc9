// The max_penetration truth kind's fields (the table: truth_kinds.h). Its
// schema fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/max_penetration.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// No contact is deeper than the tolerance (metres, absolute): the metric is
/// the largest contact depth the backend reports at the recorded samples
/// from `from` seconds on (e.g. after an overlapping start is resolved).
struct MaxPenetrationTruth {
  static constexpr std::string_view kName = "max_penetration";
  double from = 0.0;  ///< seconds, >= 0, before the run's end
  bool operator==(const MaxPenetrationTruth&) const = default;

  static std::string_view Schema();
  static Result<MaxPenetrationTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth,
                                            const MaxPenetrationTruth& kind, const Trajectory& trajectory);
};

}  // namespace talus::harness
