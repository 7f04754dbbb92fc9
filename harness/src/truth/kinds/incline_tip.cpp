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
#include <cmath>
#include <numbers>
#include <sstream>

#include "talus/harness/analytic/truths.h"
#include "talus/harness/support/nan_extremes.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {

std::string_view InclineTipTruth::Schema() {
  return R"json({
  "toleranceDescription": "required: absolute, in radians: how far a real engine's tipping and sliding thresholds may sit from the rigid-body ones; the loader refuses an angle closer than that to either threshold",
  "required": [
    "body",
    "angle",
    "mu",
    "width",
    "height",
    "tiltThreshold",
    "maxStayTilt"
  ],
  "properties": {
    "body": {
      "type": "string"
    },
    "angle": {
      "type": "number",
      "minimum": 0,
      "maximum": 1.5,
      "description": "rad, slope angle"
    },
    "mu": {
      "type": "number",
      "minimum": 0,
      "description": "combined Coulomb coefficient of the pair"
    },
    "width": {
      "type": "number",
      "exclusiveMinimum": 0,
      "description": "m, the box's extent along the slope"
    },
    "height": {
      "type": "number",
      "exclusiveMinimum": 0,
      "description": "m, the box's extent along the slope normal"
    },
    "tiltThreshold": {
      "type": "object",
      "additionalProperties": false,
      "required": [
        "value",
        "reason"
      ],
      "properties": {
        "value": {
          "type": "number",
          "exclusiveMinimum": 0,
          "maximum": 3.14159,
          "description": "rad, rotation from the start orientation that counts as tipped; default 0.5"
        },
        "reason": {
          "type": "string",
          "description": "why this size: the physics the bound comes from (slop, one step of gravity, the geometry), shown in the report"
        }
      },
      "description": "radians: a largest tilt above this counts as tipped; written {\"value\", \"reason\"}: every secondary bound has its reason beside it"
    },
    "maxStayTilt": {
      "type": "object",
      "additionalProperties": false,
      "required": [
        "value",
        "reason"
      ],
      "properties": {
        "value": {
          "type": "number",
          "exclusiveMinimum": 0
        },
        "reason": {
          "type": "string",
          "description": "why this size: the physics the bound comes from (slop, one step of gravity, the geometry), shown in the report"
        }
      },
      "description": "radians: the largest tilt a box that stays or slides may show (about one slop of tilt); written {\"value\", \"reason\"}: every secondary bound has its reason beside it"
    }
  }
})json";
}

Result<InclineTipTruth> InclineTipTruth::Read(TruthReader& reader) {
  // The angle must sit further than the tolerance (radians) from the
  // rigid-body tipping threshold atan(width / height) and from the sliding
  // threshold atan(mu): closer, a real engine's contact (resting
  // penetration, rounded margins) decides the outcome, not the physics.
  InclineTipTruth tip{reader.Number("angle"), reader.Number("mu"), reader.Number("width"),
                      reader.Number("height")};
  tip.tiltThreshold = reader.Bound("tiltThreshold");
  tip.maxStayTilt = reader.Bound("maxStayTilt");
  if (tip.maxStayTilt >= tip.tiltThreshold) {
    return reader.Refuse("/maxStayTilt/value",
                         "must be below tiltThreshold (a tilt cannot both stay and tip)");
  }
  const double margin = reader.entry["tolerance"].value("absolute", 0.0);
  const double tipping = std::atan(tip.width / tip.height);
  const double sliding = std::atan(tip.mu);
  for (const double threshold : {tipping, sliding}) {
    if (std::abs(tip.angle - threshold) < margin) {
      std::ostringstream problem;
      problem << "lies " << std::abs(tip.angle - threshold) * 180.0 / std::numbers::pi
              << " degrees from the threshold " << threshold * 180.0 / std::numbers::pi
              << " degrees, within the tolerance: the outcome is not decided by the physics";
      return reader.Refuse("/angle", problem.str());
    }
  }
  return tip;
}

void InclineTipTruth::Write(TruthWriter& writer) const {
  writer.out["angle"] = angle;
  writer.out["mu"] = mu;
  writer.out["width"] = width;
  writer.out["height"] = height;
  writer.Bound("tiltThreshold", tiltThreshold);
  writer.Bound("maxStayTilt", maxStayTilt);
}

std::vector<MetricResult> InclineTipTruth::Evaluate(const Run& run, const Truth& truth,
                                                    const InclineTipTruth& kind,
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
