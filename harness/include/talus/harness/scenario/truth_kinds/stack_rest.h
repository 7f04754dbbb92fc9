// The stack_rest truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/stack_rest.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// Boxes stacked in layers (bottom first) rest with their centres of mass
/// at floor + (layer + 1/2) layerHeight and move less than maxDrift over
/// the second half of the run. Concerns several bodies: Truth::body is -1.
struct StackRestTruth {
  static constexpr std::string_view kName = "stack_rest";
  std::vector<std::vector<int>> layers;  ///< body indices per layer, bottom layer first
  double floor = 0.0;                    ///< metres, top of the floor along the up axis
  double layerHeight = 1.0;              ///< metres, > 0
  double maxDrift = 0.01;                ///< metres, >= 0
  bool operator==(const StackRestTruth&) const = default;

  static std::string_view Schema();
  static Result<StackRestTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth, const StackRestTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
