// The incline_tip truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/incline_tip.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// A box of `width` x `height` (metres, along the slope and its normal)
/// released on an incline stays, slides or tips as InclineBoxOutcome says;
/// "tipped" means turned more than tiltThreshold radians from its start.
/// The truth's tolerance (radians, absolute) is how far a real engine's
/// tipping or sliding threshold may sit from the rigid-body one: the loader
/// refuses an angle closer than that to either threshold, where the
/// outcome is not decided by the physics.
struct InclineTipTruth {
  static constexpr std::string_view kName = "incline_tip";
  double angle = 0.0, mu = 0.5, width = 1.0, height = 1.0;
  double tiltThreshold = 0.5;  ///< radians, in (0, pi]: more counts as tipped
  /// Radians: a box that stays (or slides) may tilt by at most this much,
  /// about a slop's worth; more is neither staying nor tipping and fails.
  double maxStayTilt = 0.5;
  bool operator==(const InclineTipTruth&) const = default;

  static std::string_view Schema();
  static Result<InclineTipTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth, const InclineTipTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
