// Incline tip: the largest rotation of the body from its start orientation
// over the run (radians). The truth is the closed-form outcome
// (InclineBoxOutcome, truths.h): when it says "tips" the rotation must pass
// tiltThreshold; when it says "stays" or "slides" it must stay within
// maxStayTilt, a slop's worth of tilt (a box rocking on its edge and
// falling back has not stayed). The metric reports the
// rotation as measured, with truth pi/2 for "tips" (a box over its edge has
// turned at least that far) and 0 otherwise; pass is the threshold test,
// not the distance to those numbers.
#include <algorithm>
#include <cassert>
#include <numbers>

#include "talus/harness/analytic/truths.h"
#include "talus/harness/support/nan_extremes.h"
#include "truth/checks/evaluators.h"

namespace talus::harness {

std::vector<MetricResult> EvaluateInclineTip(const Run& run, const Truth& truth, const InclineTipTruth& kind,
                                             const Trajectory& trajectory) {
  (void)run;
  assert(truth.body >= 0);
  const auto body = static_cast<std::size_t>(truth.body);
  const Quat start = trajectory.samples.front().bodies[body].orientation;
  double tilt = 0.0;
  for (const Sample& sample : trajectory.samples) {
    tilt = MaxKeepingNaN(tilt, sample.bodies[body].orientation.angularDistance(start));
  }
  const bool tips = InclineBoxOutcome(kind.angle, kind.mu, kind.width, kind.height) == InclineOutcome::Tips;
  MetricResult metric =
      MakeMetric(std::string("incline_tip.tilt.") +
                     InclineOutcomeName(InclineBoxOutcome(kind.angle, kind.mu, kind.width, kind.height)),
                 "rad");
  metric.measured = tilt;
  metric.truth = tips ? 0.5 * std::numbers::pi : 0.0;
  const double bound = tips ? kind.tiltThreshold : kind.maxStayTilt;
  Judge(metric, Tolerance{.absolute = bound, .relative = 0.0});
  metric.reason = BoundReason(truth, tips ? "tiltThreshold" : "maxStayTilt");
  // Judge measured the distance to truth; the outcome is a threshold test:
  // a box that tips turns past tiltThreshold, one that stays or slides
  // tilts by no more than maxStayTilt (about one slop of tilt).
  metric.pass = tips ? tilt > kind.tiltThreshold : tilt <= kind.maxStayTilt;
  return {metric};
}

}  // namespace talus::harness
