// The converged_reference truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/converged_reference.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// No closed form: the truth is the same engine at timeStep / divisor.
struct ConvergedReferenceTruth {
  static constexpr std::string_view kName = "converged_reference";
  int timeStepDivisor = 16;
  bool operator==(const ConvergedReferenceTruth&) const = default;

  static std::string_view Schema();
  static Result<ConvergedReferenceTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth,
                                            const ConvergedReferenceTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
