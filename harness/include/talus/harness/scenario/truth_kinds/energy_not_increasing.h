// The energy_not_increasing truth kind's fields (the table: truth_kinds.h). Its
// schema fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/energy_not_increasing.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// The total mechanical energy of the listed bodies (every dynamic body
/// when none are listed), kinetic plus potential -m g.(x - x0), never rises
/// above its start: the metric is the largest rise max(0, E(t) - E(0))
/// over the recorded samples, in joules, judged against the tolerance
/// (absolute, J). Contacts without restitution and friction only take
/// energy out; e = 1 at most keeps it.
struct EnergyNotIncreasingTruth {
  static constexpr std::string_view kName = "energy_not_increasing";
  std::vector<int> bodies;  ///< body indices (dynamic), file order
  bool operator==(const EnergyNotIncreasingTruth&) const = default;

  static std::string_view Schema();
  static Result<EnergyNotIncreasingTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth,
                                            const EnergyNotIncreasingTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
