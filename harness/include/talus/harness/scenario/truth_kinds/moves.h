// The moves truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/moves.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// A negative test: `body`'s centre of mass must leave its start position
/// by at least `distance` metres by `within` seconds (a structure that must
/// collapse because no equilibrium holds it). The metric is the shortfall,
/// max(0, distance - the largest displacement up to `within`), judged
/// against the tolerance (metres, absolute): a body that stays fails.
struct MovesTruth {
  static constexpr std::string_view kName = "moves";
  double distance = 0.0;  ///< metres, > 0
  double within = 0.0;    ///< seconds, in (0, the run's end]
  bool operator==(const MovesTruth&) const = default;

  static std::string_view Schema();
  static Result<MovesTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth, const MovesTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
