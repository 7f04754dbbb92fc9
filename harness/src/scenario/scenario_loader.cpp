// Scenario files to runs: syntax, schema, sweep expansion, semantic checks.
//
// The order matters for the messages: a syntax error is reported with line
// and column before anything else; the schema then guarantees every field
// has the right type and range, so the mapping below may read fields without
// re-checking types and only adds what a schema cannot say (unit
// quaternions, unique names, exactly one of mass and density, truths naming
// existing bodies, no degenerate body: degenerate_body_check.h). Each sweep combination is re-validated after
// its values are written in, so a sweep cannot smuggle in a value the schema forbids.
#include "talus/harness/scenario/scenario_loader.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <unordered_map>
#include <unordered_set>
#include <variant>

#include "scenario/degenerate_body_check.h"
#include "scenario/scenario_schema_text.h"
#include "support/text_util.h"
#include "talus/harness/scenario/scenario_limits.h"
#include "talus/harness/scenario/truth_kind_io.h"
#include "talus/harness/support/json_schema.h"

namespace talus::harness {

const char* BroadPhaseChoiceName(BroadPhaseChoice choice) {
  switch (choice) {
    case BroadPhaseChoice::Auto:
      return "auto";
    case BroadPhaseChoice::UniformGrid:
      return "uniform_grid";
    case BroadPhaseChoice::AabbTree:
      return "aabb_tree";
    case BroadPhaseChoice::BruteForce:
      return "brute_force";
  }
  return "auto";
}

const char* BounceTimingChoiceName(BounceTimingChoice choice) {
  switch (choice) {
    case BounceTimingChoice::Auto:
      return "auto";
    case BounceTimingChoice::TimeOfImpact:
      return "time_of_impact";
    case BounceTimingChoice::StepBoundary:
      return "step_boundary";
  }
  return "auto";
}

namespace {

using nlohmann::json;

// How far a quaternion's norm may be from 1 and still count as unit: values
// written with ~7 significant digits (e.g. 0.7071068) must pass.
constexpr double kUnitQuaternionTolerance = 1e-6;
// Line and column (both from 1) of byte `offset` in `text`.
std::string LineAndColumn(std::string_view text, size_t offset) {
  size_t line = 1;
  size_t column = 1;
  for (size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

Error FieldError(std::string_view file, const std::string& pointer, const std::string& problem) {
  return Error{Concat(
      {file, ": ", pointer.empty() ? std::string("(root)") : PointerForMessage(pointer), ": ", problem})};
}

Vec3 ReadVec3(const json& value) {
  return Vec3(value[0].get<double>(), value[1].get<double>(), value[2].get<double>());
}

CombineRule ReadCombineRule(const json& value) {
  const std::string name = value.get<std::string>();
  if (name == "min") return CombineRule::Min;
  if (name == "max") return CombineRule::Max;
  if (name == "multiply") return CombineRule::Multiply;
  if (name == "average") return CombineRule::Average;
  return CombineRule::Sqrt;
}

// Every number in the document must be finite (JSON text such as 1e999
// parses to infinity); the first offending pointer is named.
std::optional<std::string> FindNonFinite(const json& value, const std::string& pointer) {
  if (value.is_number_float() && !std::isfinite(value.get<double>())) return pointer;
  if (value.is_array()) {
    for (size_t i = 0; i < value.size(); ++i) {
      if (auto found = FindNonFinite(value[i], pointer + "/" + std::to_string(i))) return found;
    }
  } else if (value.is_object()) {
    for (const auto& [key, child] : value.items()) {
      if (auto found = FindNonFinite(child, pointer + "/" + key)) return found;
    }
  }
  return std::nullopt;
}

Result<WorldSpec> MapWorld(const json& world, std::string_view file) {
  WorldSpec settings;
  if (world.contains("gravity")) settings.gravity = ReadVec3(world["gravity"]);
  if (const double g = ScaleSafeNorm(settings.gravity); g > kMaxGravity) {
    return FieldError(file, "/world/gravity",
                      Concat({"magnitude ", FormatNumber(g), " m/s^2 is more than the limit of ",
                              FormatNumber(kMaxGravity), " m/s^2"}));
  }
  settings.timeStep = world["timeStep"].get<double>();
  if (world.contains("iterations") && world["iterations"].is_number()) {
    settings.iterations = world["iterations"].get<int>();
  }
  const json& duration = world["duration"];
  const std::string limit = std::to_string(kMaxSteps);
  if (duration.contains("steps")) {
    // Read as a double first: a count past the int range must not wrap.
    const double steps = duration["steps"].get<double>();
    if (steps > static_cast<double>(kMaxSteps)) {
      return FieldError(file, "/world/duration/steps",
                        Concat({FormatNumber(steps, 17), " steps is more than the limit of ", limit}));
    }
    settings.steps = static_cast<int>(steps);
  } else {
    const double steps = std::round(duration["seconds"].get<double>() / settings.timeStep);
    if (!(steps >= 1.0 && steps <= static_cast<double>(kMaxSteps))) {
      return FieldError(file, "/world/duration/seconds",
                        Concat({"gives ", FormatNumber(steps, 17), " steps; need 1 to ", limit}));
    }
    settings.steps = static_cast<int>(steps);
  }
  if (world.contains("frictionCombine")) settings.frictionCombine = ReadCombineRule(world["frictionCombine"]);
  if (world.contains("restitutionCombine"))
    settings.restitutionCombine = ReadCombineRule(world["restitutionCombine"]);
  settings.gyroscopic = world.value("gyroscopic", true);
  if (world.contains("broadPhase")) {
    // The schema admits only the four names; each maps to its choice.
    const std::string name = world["broadPhase"].get<std::string>();
    for (const BroadPhaseChoice choice : {BroadPhaseChoice::Auto, BroadPhaseChoice::UniformGrid,
                                          BroadPhaseChoice::AabbTree, BroadPhaseChoice::BruteForce}) {
      if (name == BroadPhaseChoiceName(choice)) settings.broadPhase = choice;
    }
  }
  if (world.contains("bounceTiming")) {
    // The schema admits only the three names; each maps to its choice.
    const std::string name = world["bounceTiming"].get<std::string>();
    for (const BounceTimingChoice choice :
         {BounceTimingChoice::Auto, BounceTimingChoice::TimeOfImpact, BounceTimingChoice::StepBoundary}) {
      if (name == BounceTimingChoiceName(choice)) settings.bounceTiming = choice;
    }
  }
  return settings;
}

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

Result<ShapeSpec> MapShape(const json& shape) {
  const std::string kind = shape["kind"].get<std::string>();
  if (kind == "box") return ShapeSpec(BoxShape{ReadVec3(shape["halfExtents"])});
  if (kind == "sphere") return ShapeSpec(SphereShape{shape["radius"].get<double>()});
  HullShape hull;
  for (const json& point : shape["points"]) hull.points.push_back(ReadVec3(point));
  return ShapeSpec(std::move(hull));
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

Result<BodySpec> MapBody(const json& body, std::string_view file, const std::string& pointer) {
  BodySpec spec;
  spec.name = body["name"].get<std::string>();
  spec.shape = MapShape(body["shape"]).Value();
  const std::string motion = body["motion"].get<std::string>();
  spec.motion = motion == "static"      ? Motion::Static
                : motion == "kinematic" ? Motion::Kinematic
                                        : Motion::Dynamic;
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

Quantity MapQuantity(const std::string& name) {
  if (name == "orientation") return Quantity::Orientation;
  if (name == "velocity") return Quantity::Velocity;
  if (name == "energy") return Quantity::Energy;
  if (name == "momentum") return Quantity::Momentum;
  if (name == "contacts") return Quantity::Contacts;
  if (name == "penetration") return Quantity::Penetration;
  return Quantity::Position;
}

// Body indices by name, built once per scenario so look-ups stay linear.
using BodyIndex = std::unordered_map<std::string, int>;

// Looks up a body by name; -1 when there is none.
int FindBody(const BodyIndex& index, const std::string& name) {
  const auto found = index.find(name);
  return found == index.end() ? -1 : found->second;
}

// The tolerance (required by the schema) must allow something: a truth
// whose tolerance is zero could never be met and would be judged by
// round-off. Then the gate: on for every backend unless "gate" is false or
// the backend is in "ungated" (each backend once, each with its reason).
Result<bool> MapGate(const json& entry, std::string_view file, const std::string& pointer, Truth& truth) {
  const json& tolerance = entry["tolerance"];
  truth.tolerance.absolute = tolerance.value("absolute", 0.0);
  truth.tolerance.relative = tolerance.value("relative", 0.0);
  truth.toleranceReason = tolerance.value("reason", "");
  if (truth.tolerance.absolute <= 0.0 && truth.tolerance.relative <= 0.0) {
    return FieldError(file, pointer + "/tolerance",
                      "needs absolute or relative > 0 (a truth without a tolerance is never judged)");
  }
  if (truth.toleranceReason.find_first_not_of(" \t\n") == std::string::npos) {
    return FieldError(file, pointer + "/tolerance/reason", "is empty; say where the tolerance comes from");
  }
  truth.gate = entry.value("gate", true);
  if (!entry.contains("ungated")) return true;
  for (size_t i = 0; i < entry["ungated"].size(); ++i) {
    const json& item = entry["ungated"][i];
    UngatedBackend ungated{item["backend"].get<std::string>(), item["reason"].get<std::string>()};
    const std::string where = pointer + "/ungated/" + std::to_string(i);
    for (const UngatedBackend& other : truth.ungated) {
      if (other.backend == ungated.backend) {
        return FieldError(file, where + "/backend",
                          "backend " + Quoted(ungated.backend) + " is listed twice");
      }
    }
    if (ungated.reason.empty()) return FieldError(file, where + "/reason", "must say why");
    truth.ungated.push_back(std::move(ungated));
  }
  return true;
}

// Every secondary bound the kind read carries a written reason, and gate
// false says why in "gateReason" (and only then).
Result<bool> MapBounds(const json& entry, std::string_view file, const std::string& pointer,
                       const std::vector<std::string>& bounds, Truth& truth) {
  for (const std::string& name : bounds) {
    const std::string reason = entry[name]["reason"].get<std::string>();
    if (reason.find_first_not_of(" \t\n") == std::string::npos) {
      return FieldError(file, pointer + "/" + name + "/reason", "is empty; say where the bound comes from");
    }
    truth.boundReasons[name] = reason;
  }
  if (entry.contains("gateReason")) {
    truth.gateReason = entry["gateReason"].get<std::string>();
    if (truth.gate) return FieldError(file, pointer + "/gateReason", "is given but the truth is gated");
  }
  if (!truth.gate && truth.gateReason.find_first_not_of(" \t\n") == std::string::npos) {
    return FieldError(file, pointer + "/gate",
                      "is false without a \"gateReason\" (say why no backend is held to the truth)");
  }
  return true;
}

// The kind the entry's "kind" names, read by that kind's unit (the table,
// truth_kinds.h). The schema admits only the table's names.
Result<TruthKind> ReadTruthKind(const std::string& name, TruthReader& reader) {
  std::optional<Result<TruthKind>> read;
  ForEachTruthKind([&](auto tag) {
    using Kind = typename decltype(tag)::type;
    if (read || name != Kind::kName) return;
    auto kind = Kind::Read(reader);
    read = kind ? Result<TruthKind>(TruthKind(std::move(kind).Value())) : Result<TruthKind>(kind.GetError());
  });
  if (read) return std::move(*read);
  return reader.Refuse("/kind", "no truth kind named " + Quoted(name));
}

// The body a load or impulse at `pointer` names: an existing dynamic body.
Result<int> MapLoadedBody(const json& entry, const std::vector<BodySpec>& bodies, const BodyIndex& names,
                          std::string_view file, const std::string& pointer, std::string_view what) {
  const std::string name = entry["body"].get<std::string>();
  const int body = FindBody(names, name);
  if (body < 0) return FieldError(file, pointer + "/body", "no body named " + Quoted(name));
  const Motion motion = bodies[static_cast<std::size_t>(body)].motion;
  if (motion != Motion::Dynamic) {
    return FieldError(
        file, pointer + "/body",
        Concat({"body ", Quoted(name), " is ", motion == Motion::Static ? "static" : "kinematic", "; ", what,
                " moves only a dynamic body"}));
  }
  return body;
}

// The run's duration in seconds, as the steps give it.
double RunSeconds(const WorldSpec& world) { return world.steps * world.timeStep; }

// The file's "loads": each names a dynamic body, has a force or a torque,
// a point only with a force, and a window inside the run.
Result<std::vector<AppliedLoad>> MapLoads(const json& doc, const std::vector<BodySpec>& bodies,
                                          const BodyIndex& names, const WorldSpec& world,
                                          std::string_view file) {
  std::vector<AppliedLoad> loads;
  if (!doc.contains("loads")) return loads;
  const double runEnd = RunSeconds(world);
  for (size_t i = 0; i < doc["loads"].size(); ++i) {
    const json& entry = doc["loads"][i];
    const std::string pointer = "/loads/" + std::to_string(i);
    AppliedLoad load;
    auto body = MapLoadedBody(entry, bodies, names, file, pointer, "a load");
    if (!body) return body.GetError();
    load.body = body.Value();
    if (!entry.contains("force") && !entry.contains("torque")) {
      return FieldError(file, pointer, "a load needs \"force\", \"torque\" or both");
    }
    if (entry.contains("force")) load.force = ReadVec3(entry["force"]);
    if (entry.contains("torque")) load.torque = ReadVec3(entry["torque"]);
    if (entry.contains("frame") && entry["frame"] == "body") load.frame = LoadFrame::Body;
    if (entry.contains("at")) {
      if (!entry.contains("force")) {
        return FieldError(file, pointer + "/at", "a point of application needs a \"force\" to apply there");
      }
      load.point = ReadVec3(entry["at"]);
      if (const double far = load.point->cwiseAbs().maxCoeff(); far > kMaxLength) {
        return FieldError(file, pointer + "/at",
                          Concat({"coordinate ", FormatNumber(far), " m is beyond the limit of ",
                                  FormatNumber(kMaxLength), " m"}));
      }
    }
    if (entry.contains("start")) load.start = entry["start"].get<double>();
    if (entry.contains("end")) load.end = entry["end"].get<double>();
    // Within round-off of the run's end counts as the end: a duration in
    // seconds is rounded to whole steps.
    const double slack = 1e-9 * runEnd;
    if (load.start >= runEnd - slack) {
      return FieldError(file, pointer + "/start",
                        Concat({"starts at ", FormatNumber(load.start), " s, not before the run ends at ",
                                FormatNumber(runEnd), " s: it would never act"}));
    }
    if (entry.contains("end")) {
      if (load.end <= load.start) {
        return FieldError(file, pointer + "/end",
                          Concat({"ends at ", FormatNumber(load.end), " s, not after its start at ",
                                  FormatNumber(load.start), " s"}));
      }
      if (load.end > runEnd + slack) {
        return FieldError(file, pointer + "/end",
                          Concat({"ends at ", FormatNumber(load.end), " s, after the run ends at ",
                                  FormatNumber(runEnd), " s (leave \"end\" out to act to the end)"}));
      }
    }
    loads.push_back(load);
  }
  return loads;
}

// The file's "impulses": each names a dynamic body and a time inside the run.
Result<std::vector<AppliedImpulse>> MapImpulses(const json& doc, const std::vector<BodySpec>& bodies,
                                                const BodyIndex& names, const WorldSpec& world,
                                                std::string_view file) {
  std::vector<AppliedImpulse> impulses;
  if (!doc.contains("impulses")) return impulses;
  for (size_t i = 0; i < doc["impulses"].size(); ++i) {
    const json& entry = doc["impulses"][i];
    const std::string pointer = "/impulses/" + std::to_string(i);
    AppliedImpulse impulse;
    auto body = MapLoadedBody(entry, bodies, names, file, pointer, "an impulse");
    if (!body) return body.GetError();
    impulse.body = body.Value();
    impulse.linear = ReadVec3(entry["linear"]);
    if (entry.contains("at")) {
      impulse.point = ReadVec3(entry["at"]);
      if (const double far = impulse.point->cwiseAbs().maxCoeff(); far > kMaxLength) {
        return FieldError(file, pointer + "/at",
                          Concat({"coordinate ", FormatNumber(far), " m is beyond the limit of ",
                                  FormatNumber(kMaxLength), " m"}));
      }
    }
    if (entry.contains("time")) impulse.time = entry["time"].get<double>();
    // Given at the start of the step nearest its time, which must be a step of the run.
    if (std::round(impulse.time / world.timeStep) >= static_cast<double>(world.steps)) {
      return FieldError(
          file, pointer + "/time",
          Concat({"at ", FormatNumber(impulse.time), " s is not before the run's last step, at ",
                  FormatNumber((world.steps - 1) * world.timeStep), " s"}));
    }
    impulses.push_back(impulse);
  }
  return impulses;
}

// Maps a schema-valid document to a Scenario, adding the semantic checks.
Result<Scenario> MapScenario(const json& doc, std::string_view file) {
  if (auto pointer = FindNonFinite(doc, "")) return FieldError(file, *pointer, "must be a finite number");
  Scenario scenario;
  scenario.name = doc["name"].get<std::string>();
  scenario.description = doc.value("description", "");
  scenario.file = std::string(file);
  auto world = MapWorld(doc["world"], file);
  if (!world) return world.GetError();
  scenario.world = world.Value();
  BodyIndex names;  // linear in the body count (100,000 bodies load at once)
  for (size_t i = 0; i < doc["bodies"].size(); ++i) {
    const std::string pointer = "/bodies/" + std::to_string(i);
    auto body = MapBody(doc["bodies"][i], file, pointer);
    if (!body) return body.GetError();
    if (!names.emplace(body.Value().name, static_cast<int>(i)).second) {
      return FieldError(file, pointer + "/name", "duplicate body name " + Quoted(body.Value().name));
    }
    scenario.bodies.push_back(std::move(body).Value());
  }
  auto loads = MapLoads(doc, scenario.bodies, names, scenario.world, file);
  if (!loads) return loads.GetError();
  scenario.loads = std::move(loads).Value();
  auto impulses = MapImpulses(doc, scenario.bodies, names, scenario.world, file);
  if (!impulses) return impulses.GetError();
  scenario.impulses = std::move(impulses).Value();
  if (doc.contains("backends")) {
    for (size_t i = 0; i < doc["backends"].size(); ++i) {
      const std::string name = doc["backends"][i].get<std::string>();
      if (std::find(scenario.backends.begin(), scenario.backends.end(), name) != scenario.backends.end()) {
        return FieldError(file, "/backends/" + std::to_string(i), "duplicate backend " + Quoted(name));
      }
      scenario.backends.push_back(name);
    }
  }
  if (doc.contains("measure")) {
    for (const json& name : doc["measure"]) scenario.measure.push_back(MapQuantity(name.get<std::string>()));
  }
  if (doc.contains("truths")) {
    for (size_t i = 0; i < doc["truths"].size(); ++i) {
      const json& entry = doc["truths"][i];
      const std::string pointer = "/truths/" + std::to_string(i);
      Truth truth;
      if (entry.contains("body")) {
        const std::string name = entry["body"].get<std::string>();
        truth.body = FindBody(names, name);
        if (truth.body < 0) return FieldError(file, pointer + "/body", "no body named " + Quoted(name));
      }
      TruthReader reader{entry, scenario.bodies, names, scenario.world, file, pointer, truth.body};
      auto kind = ReadTruthKind(entry["kind"].get<std::string>(), reader);
      if (!kind) return kind.GetError();
      truth.kind = std::move(kind).Value();
      auto gated = MapGate(entry, file, pointer, truth);
      if (!gated) return gated.GetError();
      auto bounded = MapBounds(entry, file, pointer, reader.bounds, truth);
      if (!bounded) return bounded.GetError();
      if (entry.contains("published")) {
        const json& published = entry["published"];
        PublishedFigure figure;
        figure.value = published["value"].get<double>();
        if (published.contains("upper")) {
          figure.upper = published["upper"].get<double>();
          if (figure.upper < figure.value) {
            return FieldError(file, pointer + "/published/upper", "is below \"value\" (the range's low end)");
          }
        }
        figure.source = published["source"].get<std::string>();
        if (figure.source.find_first_not_of(" \t\n") == std::string::npos) {
          return FieldError(file, pointer + "/published/source", "is empty; name who published the figure");
        }
        truth.published = figure;
      }
      scenario.truths.push_back(truth);
    }
  }
  return scenario;
}

struct Sweep {
  std::string name;
  std::vector<json::json_pointer> targets;
  std::vector<json> values;
  bool perTarget = false;           // each value holds one entry per target
  std::vector<std::string> labels;  // one per value, or empty
};

// Reads the sweeps and checks that every target names an existing field
// outside the sweeps themselves.
Result<std::vector<Sweep>> ReadSweeps(const json& doc, std::string_view file) {
  std::vector<Sweep> sweeps;
  if (!doc.contains("sweeps")) return sweeps;
  for (size_t i = 0; i < doc["sweeps"].size(); ++i) {
    const json& entry = doc["sweeps"][i];
    Sweep sweep{entry["name"].get<std::string>(),
                {},
                entry["values"].get<std::vector<json>>(),
                entry.value("perTarget", false),
                {}};
    for (size_t t = 0; t < entry["targets"].size(); ++t) {
      const std::string where = "/sweeps/" + std::to_string(i) + "/targets/" + std::to_string(t);
      const std::string text = entry["targets"][t].get<std::string>();
      try {
        json::json_pointer target(text);
        if (text.rfind("/sweeps", 0) == 0 || !doc.contains(target)) {
          return FieldError(file, where, Quoted(text) + " does not name a field of the scenario");
        }
        sweep.targets.push_back(target);
      } catch (const json::exception&) {
        return FieldError(file, where, Quoted(text) + " is not a JSON pointer");
      }
    }
    if (entry.contains("labels")) {
      sweep.labels = entry["labels"].get<std::vector<std::string>>();
      if (sweep.labels.size() != sweep.values.size()) {
        return FieldError(file, "/sweeps/" + std::to_string(i) + "/labels",
                          "needs one label per value (" + std::to_string(sweep.values.size()) + ")");
      }
      std::unordered_set<std::string> seen;
      for (size_t l = 0; l < sweep.labels.size(); ++l) {
        if (!seen.insert(sweep.labels[l]).second) {
          return FieldError(file, "/sweeps/" + std::to_string(i) + "/labels/" + std::to_string(l),
                            "duplicate label " + Quoted(sweep.labels[l]));
        }
      }
    }
    for (size_t v = 0; sweep.perTarget && v < sweep.values.size(); ++v) {
      if (!sweep.values[v].is_array() || sweep.values[v].size() != sweep.targets.size()) {
        return FieldError(file, "/sweeps/" + std::to_string(i) + "/values/" + std::to_string(v),
                          "a perTarget value must be an array of " + std::to_string(sweep.targets.size()) +
                              " entries, one per target");
      }
    }
    sweeps.push_back(std::move(sweep));
  }
  return sweeps;
}

}  // namespace

const nlohmann::json& ScenarioSchema() {
  static const nlohmann::json schema = nlohmann::json::parse(ScenarioSchemaText());
  return schema;
}

namespace {

// Deepest nesting of `doc`, walked with an explicit stack (the document may
// be nested deeper than the call stack allows); stops counting past `limit`.
int NestingDepth(const json& doc, int limit) {
  int deepest = 0;
  std::vector<std::pair<const json*, int>> pending{{&doc, 0}};
  while (!pending.empty()) {
    const auto [value, depth] = pending.back();
    pending.pop_back();
    deepest = std::max(deepest, depth);
    if (deepest > limit) return deepest;
    if (value->is_structured()) {
      for (const json& child : *value) pending.emplace_back(&child, depth + 1);
    }
  }
  return deepest;
}

// The number of runs the sweep grid makes, or nothing when it passes `limit`
// (computed from the sizes, before any run is built).
std::optional<std::size_t> GridSize(const std::vector<Sweep>& sweeps, std::size_t limit) {
  std::size_t runs = 1;
  for (const Sweep& sweep : sweeps) {
    if (sweep.values.empty() || runs > limit / sweep.values.size()) return std::nullopt;
    runs *= sweep.values.size();
  }
  return runs;
}

// nlohmann's syntax error reads "<reason>; last read: '<token>'" and then,
// when it knows one, "; expected <kind of token>". The reason and the kind
// are its own fixed words; the token is the input as read, of any length and
// holding any quote marks, which left TidyMessage pairing the wrong marks and
// printing kilobytes of input (a fuzz finding, tests/data/fuzz/scenario_loader).
// The token is quoted again here with its own marks escaped.
std::string RequoteLastRead(const std::string& what) {
  static constexpr std::string_view kLastRead = "; last read: '";
  // lexer::token_type_name, every kind nlohmann may name as expected.
  static constexpr std::string_view kTokenKinds[] = {"<uninitialized>",
                                                     "true literal",
                                                     "false literal",
                                                     "null literal",
                                                     "string literal",
                                                     "number literal",
                                                     "'['",
                                                     "'{'",
                                                     "']'",
                                                     "'}'",
                                                     "':'",
                                                     "','",
                                                     "<parse error>",
                                                     "end of input",
                                                     "'[', '{', or a literal",
                                                     "unknown token"};
  const size_t start = what.find(kLastRead);
  if (start == std::string::npos) return what;
  std::string_view token = std::string_view(what).substr(start + kLastRead.size());
  std::string expected;
  for (const std::string_view kind : kTokenKinds) {
    const std::string tail = Concat({"'; expected ", kind});
    if (token.ends_with(tail)) {
      expected = tail.substr(1);
      token.remove_suffix(tail.size());
      break;
    }
  }
  if (expected.empty()) {
    if (!token.ends_with('\'')) return what;
    token.remove_suffix(1);
  }
  return Concat({std::string_view(what).substr(0, start), "; last read: ", Quoted(token, '\''), expected});
}

Result<std::vector<Run>> ParseScenarioDocument(std::string_view text, std::string_view fileName) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& error) {
    // nlohmann's byte is one past the last character of the offending token.
    const size_t offset = error.byte > 0 ? error.byte - 1 : 0;
    std::string what = error.what();
    const size_t colon = what.find(": ");
    if (colon != std::string::npos) what = what.substr(colon + 2);
    return Error{Concat({fileName, ": ", LineAndColumn(text, offset), ": ", RequoteLastRead(what)})};
  } catch (const json::exception& error) {
    // A number too large for a double (e.g. 1e999) has no position.
    std::string what = error.what();
    const size_t bracket = what.find("] ");
    if (bracket != std::string::npos) what = what.substr(bracket + 2);
    return Error{std::string(fileName) + ": " + what};
  }
  if (NestingDepth(doc, kMaxJsonDepth) > kMaxJsonDepth) {
    return Error{Concat({fileName, ": nested more than ", std::to_string(kMaxJsonDepth),
                         " arrays or objects deep (the limit)"})};
  }
  if (auto violation = ValidateAgainstSchema(ScenarioSchema(), doc)) {
    return FieldError(fileName, violation->pointer, violation->problem);
  }
  auto sweeps = ReadSweeps(doc, fileName);
  if (!sweeps) return sweeps.GetError();
  if (!GridSize(sweeps.Value(), kMaxRuns)) {
    std::string sizes;
    for (const Sweep& sweep : sweeps.Value()) {
      sizes.append(sizes.empty() ? "" : " x ").append(std::to_string(sweep.values.size()));
    }
    return FieldError(fileName, "/sweeps",
                      Concat({"the grid (", sizes, " values) makes more than the limit of ",
                              std::to_string(kMaxRuns), " runs"}));
  }
  std::unordered_set<std::string> runIds;

  // Odometer over the sweep grid, the last sweep fastest.
  std::vector<size_t> index(sweeps.Value().size(), 0);
  std::vector<Run> runs;
  while (true) {
    json instance = doc;
    instance.erase("sweeps");
    Run run;
    run.id = doc["name"].get<std::string>();
    std::string label;
    for (size_t s = 0; s < index.size(); ++s) {
      const Sweep& sweep = sweeps.Value()[s];
      const json& value = sweep.values[index[s]];
      for (size_t t = 0; t < sweep.targets.size(); ++t) {
        instance[sweep.targets[t]] = sweep.perTarget ? value[t] : value;
      }
      // A perTarget value is labelled by its first entry (the swept parameter).
      const std::string shown = !sweep.labels.empty() ? sweep.labels[index[s]]
                                : sweep.perTarget     ? value[0].dump()
                                                      : value.dump();
      run.sweepValues.push_back({sweep.name, shown});
      label += (label.empty() ? "" : ",") + sweep.name + "=" + shown;
    }
    if (!label.empty()) run.id += "[" + label + "]";
    const std::string where =
        label.empty() ? std::string(fileName) : std::string(fileName) + " (" + label + ")";
    if (auto violation = ValidateAgainstSchema(ScenarioSchema(), instance)) {
      return FieldError(where, violation->pointer, violation->problem);
    }
    auto scenario = MapScenario(instance, where);
    if (!scenario) return scenario.GetError();
    run.scenario = std::move(scenario).Value();
    run.scenario.file = std::string(fileName);
    run.timeStep = run.scenario.world.timeStep;
    run.iterations = run.scenario.world.iterations;
    run.steps = run.scenario.world.steps;
    if (!runIds.insert(run.id).second) {
      return FieldError(
          fileName, "/sweeps",
          Concat({"two runs are both named ", Quoted(run.id), " (a sweep repeats a value or label)"}));
    }
    runs.push_back(std::move(run));

    size_t s = index.size();
    while (s > 0 && ++index[s - 1] == sweeps.Value()[s - 1].values.size()) index[--s] = 0;
    if (s == 0) break;
  }
  return runs;
}

}  // namespace

Result<std::vector<Run>> ParseScenarioText(std::string_view text, std::string_view fileName) {
  auto runs = ParseScenarioDocument(text, fileName);
  if (!runs) return Error{TidyMessage(runs.GetError().message)};
  return runs;
}

Result<std::vector<Run>> LoadScenarioFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path.string() + ": cannot open the file"};
  std::ostringstream text;
  text << in.rdbuf();
  return ParseScenarioText(text.str(), path.string());
}

Result<std::vector<Run>> LoadScenarios(const std::vector<std::filesystem::path>& paths) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  for (const fs::path& path : paths) {
    std::error_code error;
    if (fs::is_directory(path, error)) {
      std::vector<fs::path> found;
      for (auto it = fs::recursive_directory_iterator(path, error); !error && it != fs::end(it);
           it.increment(error)) {
        if (it->is_regular_file() && it->path().extension() == ".json" &&
            it->path().filename() != "schema.json") {
          found.push_back(it->path());
        }
      }
      if (error) return Error{Concat({path.string(), ": ", error.message()})};
      if (found.empty()) {
        return Error{
            Concat({path.string(), ": no scenario files (*.json other than schema.json) in this folder"})};
      }
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else if (fs::is_regular_file(path, error)) {
      files.push_back(path);
    } else {
      return Error{Concat({path.string(), ": no such scenario file or folder"})};
    }
  }
  if (files.empty()) return Error{"no scenario files found"};
  std::vector<Run> runs;
  std::map<std::string, std::string> fileOfScenario;  // two files must not share a scenario name
  for (const fs::path& file : files) {
    auto loaded = LoadScenarioFile(file);
    if (!loaded) return loaded.GetError();
    if (!loaded.Value().empty()) {
      const std::string& name = loaded.Value().front().scenario.name;
      const auto [it, added] = fileOfScenario.emplace(name, file.string());
      if (!added) {
        return Error{Concat({file.string(), ": scenario name ", Quoted(name), " is already used by ",
                             it->second, " (run ids and results are keyed by it)"})};
      }
    }
    for (Run& run : loaded.Value()) runs.push_back(std::move(run));
  }
  return runs;
}

}  // namespace talus::harness
