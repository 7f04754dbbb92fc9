// The energy_drift truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/energy_drift.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// Total mechanical energy (translational and rotational kinetic energy plus
/// the potential -m g.x) of `Truth::body`, or of every dynamic body when
/// the truth names none, is conserved: the metric is the largest
/// |E(t) - E(0)| / E0, with E0 the kinetic energy at the start (the total
/// energy with the potential measured from the start positions).
struct EnergyDriftTruth {
  static constexpr std::string_view kName = "energy_drift";
  bool operator==(const EnergyDriftTruth&) const = default;

  static std::string_view Schema();
  static Result<EnergyDriftTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth, const EnergyDriftTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
