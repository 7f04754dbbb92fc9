// The at_rest truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/at_rest.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// Listed bodies stay at rest where they start: over the window [from,
/// until] (seconds) no centre of mass moves further than the tolerance
/// (metres, absolute) from its start position (at_rest.drift), no body turns
/// more than maxTilt radians from its start orientation (at_rest.tilt) and
/// no centre of mass moves faster than maxSpeed m/s (at_rest.speed: jitter).
struct AtRestTruth {
  static constexpr std::string_view kName = "at_rest";
  std::vector<int> bodies;  ///< body indices (dynamic), file order
  double from = 0.0;        ///< seconds, window start, >= 0
  double until = 0.0;       ///< seconds, window end, in (from, the run's end]
  double maxTilt = 0.0;     ///< radians, >= 0 (a bound)
  double maxSpeed = 0.0;    ///< m/s, >= 0 (a bound)
  bool operator==(const AtRestTruth&) const = default;

  static std::string_view Schema();
  static Result<AtRestTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth, const AtRestTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
