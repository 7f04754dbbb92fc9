// Hull rest: at the end of the run, the angle between the expected resting
// face's outward normal (turned into the world by the body's orientation)
// and the down direction, checked against maxFaceAngle: the body rests on
// the face the truth names, not on a neighbour; and the centre of mass's
// height along the up axis against floor + the centroid's distance to that
// face (computed from the hull by the loader), checked against the truth's
// tolerance.
#include <algorithm>
#include <cassert>
#include <cmath>

#include "truth/checks/evaluators.h"

namespace talus::harness {

std::vector<MetricResult> EvaluateHullRest(const Run& run, const Truth& truth, const HullRestTruth& kind,
                                           const Trajectory& trajectory) {
  assert(truth.body >= 0);
  const auto body = static_cast<std::size_t>(truth.body);
  const Vec3 up = UpAxis(run);
  const BodyReading& state = trajectory.samples.back().bodies[body];
  const Vec3 worldNormal = state.orientation * kind.faceNormal;
  MetricResult face = MakeMetric("hull_rest.face_angle", "rad");
  face.measured = std::acos(std::clamp(worldNormal.dot(-up), -1.0, 1.0));
  face.truth = 0.0;
  Judge(face, Tolerance{.absolute = kind.maxFaceAngle, .relative = 0.0});
  face.reason = BoundReason(truth, "maxFaceAngle");
  MetricResult height = MakeMetric("hull_rest.height", "m");
  height.measured = state.centerOfMass.dot(up);
  height.truth = kind.floor + kind.height;
  Judge(height, truth.tolerance);
  return {face, height};
}

}  // namespace talus::harness
