// The bounce_heights truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/bounce_heights.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// A body dropped with its lowest point h metres above the floor, with
/// restitution e, reaches e^(2k) h at its k-th apex (k = 1..count).
struct BounceHeightsTruth {
  static constexpr std::string_view kName = "bounce_heights";
  double h = 1.0, e = 0.5;
  int count = 1;
  bool operator==(const BounceHeightsTruth&) const = default;

  static std::string_view Schema();
  static Result<BounceHeightsTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth,
                                            const BounceHeightsTruth& kind, const Trajectory& trajectory);
};

}  // namespace talus::harness
