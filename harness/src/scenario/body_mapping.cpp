// One body of a scenario file to BodySpec, with the checks a schema cannot
// make (body_mapping.h).
#include "scenario/body_mapping.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <variant>

#include "scenario/degenerate_body_check.h"
#include "scenario/scenario_mapping_support.h"
#include "scenario/scenario_names.h"
#include "support/text_util.h"
#include "talus/harness/scenario/scenario_limits.h"
#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {
namespace {

using nlohmann::json;

Result<Quat> MapOrientation(const json& orientation, std::string_view file, const std::string& pointer) {
  if (orientation.contains("quaternion")) {
    const json& q = orientation["quaternion"];
    const Quat quat(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(), q[3].get<double>());
    const double norm = quat.norm();
    if (std::abs(norm - 1.0) > kUnitQuaternionTolerance) {
      std::ostringstream problem;
      problem << "quaternion is not unit length (norm " << norm << ")";
      return FieldError(file, pointer + "/quaternion", problem.str());
    }
    return quat.normalized();
  }
  const Vec3 axis = ReadVec3(orientation["axis"]);
  if (ScaleSafeNorm(axis) < 1e-12) return FieldError(file, pointer + "/axis", "axis has zero length");
  return Quat(Eigen::AngleAxisd(orientation["angle"].get<double>(), ScaleSafeNormalized(axis)));
}

// One ShapeSpec, assigned in place and returned once: GCC 12 at -O1 (the
// sanitizer tree) otherwise reads a returned temporary's inactive vector
// alternative as maybe-uninitialized (a false alarm, fatal under -Werror).
Result<ShapeSpec> MapShape(const json& shape) {
  const std::string kind = shape["kind"].get<std::string>();
  ShapeSpec spec;
  if (kind == "box") {
    spec.emplace<BoxShape>(BoxShape{ReadVec3(shape["halfExtents"])});
  } else if (kind == "sphere") {
    spec.emplace<SphereShape>(SphereShape{shape["radius"].get<double>()});
  } else {
    HullShape& hull = spec.emplace<HullShape>();
    for (const json& point : shape["points"]) hull.points.push_back(ReadVec3(point));
  }
  return spec;
}

// The body's sizes, position and speeds against scenario_limits.h, each
// refusal naming the body, the field and the limit.
std::optional<Error> CheckMagnitudes(const BodySpec& spec, std::string_view file,
                                     const std::string& pointer) {
  const auto refuse = [&](const std::string& field, const std::string& problem) {
    return FieldError(file, pointer + field, Concat({"body ", Quoted(spec.name), ": ", problem}));
  };
  const auto length = [](double value) { return FormatNumber(value) + " m"; };
  double extent = 0.0;  // the body's farthest point from its frame origin
  if (const auto* box = std::get_if<BoxShape>(&spec.shape)) {
    for (int i = 0; i < 3; ++i) {
      const double e = box->halfExtents[i];
      if (e < kMinLength || e > kMaxLength) {
        return refuse(Concat({"/shape/halfExtents/", std::to_string(i)}),
                      Concat({"half extent ", length(e), " is outside ", length(kMinLength), " to ",
                              length(kMaxLength)}));
      }
    }
    extent = ScaleSafeNorm(box->halfExtents);
  } else if (const auto* sphere = std::get_if<SphereShape>(&spec.shape)) {
    if (sphere->radius < kMinLength || sphere->radius > kMaxLength) {
      return refuse("/shape/radius", Concat({"radius ", length(sphere->radius), " is outside ",
                                             length(kMinLength), " to ", length(kMaxLength)}));
    }
    extent = sphere->radius;
  } else {
    const auto& points = std::get<HullShape>(spec.shape).points;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double far = points[i].cwiseAbs().maxCoeff();
      if (far > kMaxLength) {
        return refuse(Concat({"/shape/points/", std::to_string(i)}),
                      Concat({"coordinate ", length(far), " is beyond the limit of ", length(kMaxLength)}));
      }
      extent = std::max(extent, ScaleSafeNorm(points[i]));
    }
  }
  if (const double far = spec.position.cwiseAbs().maxCoeff(); far > kMaxLength) {
    return refuse("/position",
                  Concat({"coordinate ", length(far), " is beyond the limit of ", length(kMaxLength)}));
  }
  const std::string speedLimit = FormatNumber(kMaxSpeed) + " m/s (the speed of light)";
  if (const double speed = ScaleSafeNorm(spec.linearVelocity); speed > kMaxSpeed) {
    return refuse("/linearVelocity",
                  Concat({"speed ", FormatNumber(speed), " m/s is more than ", speedLimit}));
  }
  if (const double rim = ScaleSafeNorm(spec.angularVelocity) * extent; rim > kMaxSpeed) {
    return refuse("/angularVelocity", Concat({"spin ", FormatNumber(ScaleSafeNorm(spec.angularVelocity)),
                                              " rad/s moves the body's farthest point at ", FormatNumber(rim),
                                              " m/s, more than ", speedLimit}));
  }
  return std::nullopt;
}

}  // namespace

Result<BodySpec> MapBody(const json& body, std::string_view file, const std::string& pointer) {
  BodySpec spec;
  spec.name = body["name"].get<std::string>();
  spec.shape = MapShape(body["shape"]).Value();
  spec.motion = MotionNamed(body["motion"].get<std::string>());
  spec.position = ReadVec3(body["position"]);
  if (body.contains("orientation")) {
    auto orientation = MapOrientation(body["orientation"], file, pointer + "/orientation");
    if (!orientation) return orientation.GetError();
    spec.orientation = orientation.Value();
  }
  if (body.contains("linearVelocity")) spec.linearVelocity = ReadVec3(body["linearVelocity"]);
  if (body.contains("angularVelocity")) spec.angularVelocity = ReadVec3(body["angularVelocity"]);
  const bool hasMass = body.contains("mass");
  const bool hasDensity = body.contains("density");
  if (spec.motion == Motion::Dynamic) {
    if (hasMass && hasDensity)
      return FieldError(file, pointer, "give either \"mass\" or \"density\", not both");
    if (!hasMass && !hasDensity)
      return FieldError(file, pointer, "a dynamic body needs \"mass\" or \"density\"");
    if (hasMass) spec.mass = body["mass"].get<double>();
    if (hasDensity) spec.density = body["density"].get<double>();
  } else if (hasMass || hasDensity) {
    return FieldError(file, pointer + (hasMass ? "/mass" : "/density"),
                      spec.motion == Motion::Kinematic
                          ? "a kinematic body takes no mass or density (it has infinite mass to contacts)"
                          : "a static body takes no mass or density");
  } else if (spec.motion == Motion::Static &&
             (body.contains("linearVelocity") || body.contains("angularVelocity"))) {
    return FieldError(file, pointer, "a static body cannot move (no velocities)");
  }
  if (body.contains("friction")) spec.friction = body["friction"].get<double>();
  if (body.contains("restitution")) spec.restitution = body["restitution"].get<double>();
  if (auto problem = CheckMagnitudes(spec, file, pointer)) return *problem;
  if (auto problem = FindDegenerateBody(spec))
    return FieldError(file, pointer + problem->field, problem->reason);
  return spec;
}

}  // namespace talus::harness
