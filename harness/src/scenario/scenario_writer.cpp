// Scenario model to scenario-file JSON (see scenario_writer.h). Field names
// and forms are the schema's (scenarios/schema.json); each truth kind
// writes the fields its own Read reads (harness/src/truth/kinds/<kind>.cpp).
#include "talus/harness/scenario/scenario_writer.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <variant>

#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {
namespace {

using nlohmann::ordered_json;

ordered_json Vec(const Vec3& v) { return ordered_json::array({v.x(), v.y(), v.z()}); }

const char* QuantityName(Quantity quantity) {
  switch (quantity) {
    case Quantity::Position:
      return "position";
    case Quantity::Orientation:
      return "orientation";
    case Quantity::Velocity:
      return "velocity";
    case Quantity::Energy:
      return "energy";
    case Quantity::Momentum:
      return "momentum";
    case Quantity::Contacts:
      return "contacts";
    case Quantity::Penetration:
      return "penetration";
  }
  return "position";
}

ordered_json WorldJson(const WorldSpec& world) {
  ordered_json out;
  out["gravity"] = Vec(world.gravity);
  out["timeStep"] = world.timeStep;
  if (world.iterations > 0) {
    out["iterations"] = world.iterations;
  } else {
    out["iterations"] = "engine default";
  }
  out["duration"] = {{"steps", world.steps}};
  out["frictionCombine"] = CombineRuleName(world.frictionCombine);
  out["restitutionCombine"] = CombineRuleName(world.restitutionCombine);
  out["gyroscopic"] = world.gyroscopic;
  out["broadPhase"] = BroadPhaseChoiceName(world.broadPhase);
  out["bounceTiming"] = BounceTimingChoiceName(world.bounceTiming);
  return out;
}

ordered_json ShapeJson(const ShapeSpec& shape) {
  if (const auto* box = std::get_if<BoxShape>(&shape)) {
    return {{"kind", "box"}, {"halfExtents", Vec(box->halfExtents)}};
  }
  if (const auto* sphere = std::get_if<SphereShape>(&shape)) {
    return {{"kind", "sphere"}, {"radius", sphere->radius}};
  }
  ordered_json points = ordered_json::array();
  for (const Vec3& p : std::get<HullShape>(shape).points) points.push_back(Vec(p));
  return {{"kind", "hull"}, {"points", points}};
}

ordered_json BodyJson(const BodySpec& body) {
  ordered_json out;
  out["name"] = body.name;
  out["shape"] = ShapeJson(body.shape);
  const bool dynamic = body.motion == Motion::Dynamic;
  out["motion"] = dynamic ? "dynamic" : body.motion == Motion::Kinematic ? "kinematic" : "static";
  out["position"] = Vec(body.position);
  const Quat& q = body.orientation;
  out["orientation"] = {{"quaternion", {q.w(), q.x(), q.y(), q.z()}}};
  if (body.motion != Motion::Static) {
    // A static body takes no velocities (the loader refuses them); a
    // kinematic one's are its prescribed motion.
    out["linearVelocity"] = Vec(body.linearVelocity);
    out["angularVelocity"] = Vec(body.angularVelocity);
  }
  if (dynamic) {
    // Only a dynamic body has a mass: exactly one of mass and density.
    if (body.mass > 0.0) {
      out["mass"] = body.mass;
    } else {
      out["density"] = body.density;
    }
  }
  out["friction"] = body.friction;
  out["restitution"] = body.restitution;
  return out;
}

ordered_json LoadJson(const AppliedLoad& load, const std::vector<BodySpec>& bodies) {
  ordered_json out;
  out["body"] = bodies[static_cast<std::size_t>(load.body)].name;
  out["force"] = Vec(load.force);
  out["torque"] = Vec(load.torque);
  out["frame"] = load.frame == LoadFrame::Body ? "body" : "world";
  // The loader refuses a point without a force; a zero force written out
  // reloads the same.
  if (load.point) out["at"] = Vec(*load.point);
  out["start"] = load.start;
  if (std::isfinite(load.end)) out["end"] = load.end;
  return out;
}

ordered_json ImpulseJson(const AppliedImpulse& impulse, const std::vector<BodySpec>& bodies) {
  ordered_json out;
  out["body"] = bodies[static_cast<std::size_t>(impulse.body)].name;
  out["linear"] = Vec(impulse.linear);
  if (impulse.point) out["at"] = Vec(*impulse.point);
  out["time"] = impulse.time;
  return out;
}

ordered_json TruthJson(const Truth& truth, const std::vector<BodySpec>& bodies) {
  // The kind's name, then its own fields, written by its unit (the table,
  // truth_kinds.h); then the fields every truth shares.
  ordered_json out;
  std::visit(
      [&](const auto& kind) {
        out["kind"] = std::string(kind.kName);
        TruthWriter writer{out, bodies, truth};
        kind.Write(writer);
      },
      truth.kind);
  if (truth.body >= 0) out["body"] = bodies[static_cast<std::size_t>(truth.body)].name;
  ordered_json tolerance;
  if (truth.tolerance.absolute > 0.0) tolerance["absolute"] = truth.tolerance.absolute;
  if (truth.tolerance.relative > 0.0) tolerance["relative"] = truth.tolerance.relative;
  tolerance["reason"] = truth.toleranceReason;
  out["tolerance"] = tolerance;
  out["gate"] = truth.gate;
  if (!truth.gateReason.empty()) out["gateReason"] = truth.gateReason;
  if (!truth.ungated.empty()) {
    ordered_json ungated = ordered_json::array();
    for (const UngatedBackend& entry : truth.ungated) {
      ungated.push_back({{"backend", entry.backend}, {"reason", entry.reason}});
    }
    out["ungated"] = ungated;
  }
  if (truth.published) {
    ordered_json published = {{"value", truth.published->value}};
    if (!std::isnan(truth.published->upper)) published["upper"] = truth.published->upper;
    published["source"] = truth.published->source;
    out["published"] = published;
  }
  return out;
}

}  // namespace

std::string ScenarioToJson(const Scenario& scenario) {
  ordered_json out;
  out["name"] = scenario.name;
  out["description"] = scenario.description;
  out["world"] = WorldJson(scenario.world);
  ordered_json bodies = ordered_json::array();
  for (const BodySpec& body : scenario.bodies) bodies.push_back(BodyJson(body));
  out["bodies"] = bodies;
  if (!scenario.loads.empty()) {
    ordered_json loads = ordered_json::array();
    for (const AppliedLoad& load : scenario.loads) loads.push_back(LoadJson(load, scenario.bodies));
    out["loads"] = loads;
  }
  if (!scenario.impulses.empty()) {
    ordered_json impulses = ordered_json::array();
    for (const AppliedImpulse& impulse : scenario.impulses)
      impulses.push_back(ImpulseJson(impulse, scenario.bodies));
    out["impulses"] = impulses;
  }
  if (!scenario.backends.empty()) out["backends"] = scenario.backends;
  ordered_json measure = ordered_json::array();
  for (Quantity quantity : scenario.measure) measure.push_back(QuantityName(quantity));
  out["measure"] = measure;
  ordered_json truths = ordered_json::array();
  for (const Truth& truth : scenario.truths) truths.push_back(TruthJson(truth, scenario.bodies));
  out["truths"] = truths;
  return out.dump(2) + "\n";
}

}  // namespace talus::harness
