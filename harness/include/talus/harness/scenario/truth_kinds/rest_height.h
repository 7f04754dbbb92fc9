// The rest_height truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/rest_height.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// The centre of mass comes to rest at `height` (metres along the up axis);
/// over the second half of the run its peak-to-peak motion stays below
/// maxJitter (metres).
struct RestHeightTruth {
  static constexpr std::string_view kName = "rest_height";
  double height = 0.0;
  double maxJitter = 1e-3;
  bool operator==(const RestHeightTruth&) const = default;

  static std::string_view Schema();
  static Result<RestHeightTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth, const RestHeightTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
