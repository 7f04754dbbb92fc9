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
#include <numbers>
#include <sstream>

#include "talus/harness/analytic/hull_rest_analysis.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {
namespace {

// Angle (rad, 1 degree) within which a hull_rest faceNormal names a face:
// normals written to 3 or 4 digits pass, neighbouring faces are far apart.
constexpr double kFaceNormalTolerance = 0.017453292519943295;

}  // namespace

std::string_view HullRestTruth::Schema() {
  return R"json({
  "required": [
    "body",
    "faceNormal",
    "floor",
    "height",
    "maxFaceAngle"
  ],
  "properties": {
    "body": {
      "type": "string"
    },
    "faceNormal": {
      "type": "array",
      "items": {
        "type": "number"
      },
      "minItems": 3,
      "maxItems": 3,
      "description": "outward normal (body frame) of the hull face the body should rest on; any length > 0"
    },
    "floor": {
      "type": "number",
      "description": "m, height of the floor's top along the up axis"
    },
    "maxFaceAngle": {
      "type": "object",
      "additionalProperties": false,
      "required": [
        "value",
        "reason"
      ],
      "properties": {
        "value": {
          "type": "number",
          "minimum": 0,
          "maximum": 3.14159,
          "description": "rad, largest allowed angle between that face's normal and the down direction at the end; default 0.05"
        },
        "reason": {
          "type": "string",
          "description": "why this size: the physics the bound comes from (slop, one step of gravity, the geometry), shown in the report"
        }
      },
      "description": "radians: the largest angle between the resting face's normal and down at the end; written {\"value\", \"reason\"}: every secondary bound has its reason beside it"
    },
    "height": {
      "type": "number",
      "exclusiveMinimum": 0,
      "description": "m: the volume centroid's distance to the resting face's plane, computed independently of the engine (qhull facets, divergence theorem; tests/reference checks the number)"
    }
  }
})json";
}

Result<HullRestTruth> HullRestTruth::Read(TruthReader& reader) {
  // The resting face must be a face of the body's hull, and a stable one: a
  // truth naming an unstable face could never be met. The engine's hull
  // builder only validates the file here; the answer (the face normal and
  // the height) is the file's own, computed independently of the engine
  // (qhull and the divergence theorem, checked by tests/reference), so a
  // broken hull or mass code in the engine cannot move the truth with it.
  const auto* hull = std::get_if<HullShape>(&reader.bodies[reader.body].shape);
  if (hull == nullptr) return reader.Refuse("/body", "hull_rest needs a hull body");
  const Vec3 normal = ScaleSafeNormalized(reader.Vector("faceNormal"));
  if (normal.isZero()) return reader.Refuse("/faceNormal", "normal has zero length");
  auto analysis = AnalyseHullRest(hull->points);
  if (!analysis) {
    return reader.RefuseAt("/bodies/" + std::to_string(reader.body) + "/shape/points",
                           analysis.GetError().message);
  }
  const HullRestFace& face = analysis.Value().faces[analysis.Value().NearestFace(normal)];
  const double angle = std::acos(std::clamp(face.normal.dot(normal.normalized()), -1.0, 1.0));
  if (angle > kFaceNormalTolerance) {
    std::ostringstream problem;
    problem << "names no face of the hull (nearest face normal is " << angle * 180.0 / std::numbers::pi
            << " degrees away)";
    return reader.Refuse("/faceNormal", problem.str());
  }
  if (!face.stable) {
    return reader.Refuse("/faceNormal", "names an unstable face (the centroid projects outside it)");
  }
  HullRestTruth truth;
  truth.faceNormal = normal.normalized();
  truth.floor = reader.Number("floor");
  truth.height = reader.Number("height");
  truth.maxFaceAngle = reader.Bound("maxFaceAngle");
  return truth;
}

void HullRestTruth::Write(TruthWriter& writer) const {
  writer.Vector("faceNormal", faceNormal);
  writer.out["floor"] = floor;
  writer.out["height"] = height;
  writer.Bound("maxFaceAngle", maxFaceAngle);
}

std::vector<MetricResult> HullRestTruth::Evaluate(const Run& run, const Truth& truth,
                                                  const HullRestTruth& kind, const Trajectory& trajectory) {
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
