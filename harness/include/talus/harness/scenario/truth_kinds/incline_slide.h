// The incline_slide truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/incline_slide.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// A block released at rest on an incline of `angle` radians slides
/// InclineDistance(angle, mu, g, t) metres (0 when tan(angle) <= mu).
struct InclineSlideTruth {
  static constexpr std::string_view kName = "incline_slide";
  double angle = 0.0, mu = 0.5, g = 9.81;
  bool operator==(const InclineSlideTruth&) const = default;

  static std::string_view Schema();
  static Result<InclineSlideTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth, const InclineSlideTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
