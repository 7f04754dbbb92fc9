// The topples truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/topples.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// Listed bodies topple, in the order listed (a row of dominoes struck at
/// one end): by `within` seconds each body's rotation from its start
/// orientation reaches `angle` radians (topples.shortfall), and none gets
/// there before the body listed before it (topples.order). The tolerance
/// (radians, absolute) is how far short of the angle still counts as
/// toppled, for both.
struct TopplesTruth {
  static constexpr std::string_view kName = "topples";
  std::vector<int> bodies;  ///< body indices (dynamic), in the order they must topple
  double angle = 0.0;       ///< radians, in (tolerance, pi]
  double within = 0.0;      ///< seconds, in (0, the run's end]
  bool operator==(const TopplesTruth&) const = default;

  static std::string_view Schema();
  static Result<TopplesTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth, const TopplesTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
