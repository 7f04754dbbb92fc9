// The box_landing truth kind's fields (the table: truth_kinds.h). Its schema
// fragment, reader, writer and evaluator are in
// harness/src/truth/kinds/box_landing.cpp.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {

/// A box thrown onto a static floor lands and settles (box_toss): judged
/// without the engine's own finer run. At the end it rests on a face (the
/// box axis nearest the up axis within maxFaceAngle radians of it) with its
/// centre of mass at floor + that axis's half extent, the geometric height
/// (the truth's tolerance, metres); from `restAfter` seconds on its centre
/// of mass moves less than maxMotion metres (peak to peak along each axis
/// of the world, the largest of the three); its total mechanical energy
/// never rises by more than maxEnergyRise metres of lift (the rise over the
/// lowest energy before it, divided by m |g|): a contact with no
/// restitution only takes energy out; no contact is ever deeper than
/// maxPenetration metres. Each bound's reason is in Truth::boundReasons.
struct BoxLandingTruth {
  static constexpr std::string_view kName = "box_landing";
  double floor = 0.0;           ///< metres, top of the floor along the up axis
  double restAfter = 0.0;       ///< seconds: at rest from here to the end, >= 0
  double maxFaceAngle = 0.0;    ///< radians, in [0, pi/4]
  double maxMotion = 0.0;       ///< metres, >= 0
  double maxEnergyRise = 0.0;   ///< metres of lift, >= 0
  double maxPenetration = 0.0;  ///< metres, >= 0
  bool operator==(const BoxLandingTruth&) const = default;

  static std::string_view Schema();
  static Result<BoxLandingTruth> Read(TruthReader& reader);
  void Write(TruthWriter& writer) const;
  static std::vector<MetricResult> Evaluate(const Run& run, const Truth& truth, const BoxLandingTruth& kind,
                                            const Trajectory& trajectory);
};

}  // namespace talus::harness
