// The rotational_energy_drift truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/rotational_energy_drift.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// A free body's rotational kinetic energy w.I_world w / 2 is conserved:
/// the metric is the largest |E(t) - E(0)| / E(0).
struct RotationalEnergyDriftTruth {
  static constexpr std::string_view kName = "rotational_energy_drift";
  bool operator==(const RotationalEnergyDriftTruth&) const = default;

  static std::string_view Schema();
  static Result<RotationalEnergyDriftTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth,
                                            const RotationalEnergyDriftTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
