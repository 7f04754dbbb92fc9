// The free_fall truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/free_fall.cpp.
#pragma once

#include <limits>
#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// Free fall of `body`'s centre of mass along -gravity from height y0
/// (metres, along the up axis) with vertical speed v0 (m/s) and g (m/s^2).
struct FreeFallTruth {
  static constexpr std::string_view kName = "free_fall";
  double y0 = 0.0, v0 = 0.0, g = 9.81;
  /// Seconds: only samples up to this time are judged (the flight before a
  /// landing); infinity = the whole run.
  double until = std::numeric_limits<double>::infinity();
  bool operator==(const FreeFallTruth&) const = default;

  static std::string_view Schema();
  static Result<FreeFallTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth, const FreeFallTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
