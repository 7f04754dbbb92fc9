// Incline slide: the distance the centre of mass moved from the first
// sample to the last (the block moves only along the slope, so the length
// of its displacement is the distance slid) against a t^2 / 2 with a =
// g (sin angle - mu cos angle), or 0 when tan(angle) <= mu, and against the
// symplectic-Euler sum a h^2 n (n + 1) / 2 (truths.h). Below the threshold
// the tolerance's absolute part is the creep allowed.
#include <cassert>

#include "talus/harness/analytic/truths.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {

std::string_view InclineSlideTruth::Schema() {
  return R"json({
  "required": [
    "body",
    "angle",
    "mu",
    "g"
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
    "g": {
      "type": "number",
      "exclusiveMinimum": 0,
      "description": "m/s^2"
    }
  }
})json";
}

Result<InclineSlideTruth> InclineSlideTruth::Read(TruthReader& reader) {
  return InclineSlideTruth{reader.Number("angle"), reader.Number("mu"), reader.Number("g")};
}

void InclineSlideTruth::Write(TruthWriter& writer) const {
  writer.out["angle"] = angle;
  writer.out["mu"] = mu;
  writer.out["g"] = g;
}

std::vector<MetricResult> InclineSlideTruth::Evaluate(const Run& run, const Truth& truth,
                                                      const InclineSlideTruth& kind,
                                                      const Trajectory& trajectory) {
  (void)run;
  assert(truth.body >= 0);
  const auto body = static_cast<std::size_t>(truth.body);
  const Sample& first = trajectory.samples.front();
  const Sample& last = trajectory.samples.back();
  MetricResult metric = MakeMetric("incline_slide.distance", "m");
  metric.measured = (last.bodies[body].centerOfMass - first.bodies[body].centerOfMass).norm();
  metric.truth = InclineDistance(kind.angle, kind.mu, kind.g, last.time - first.time);
  metric.truthIntegrator = InclineDistanceSymplecticEuler(kind.angle, kind.mu, kind.g, trajectory.timeStep,
                                                          last.step - first.step);
  Judge(metric, truth.tolerance);
  return {metric};
}

}  // namespace talus::harness
