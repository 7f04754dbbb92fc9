// Scenario model to scenario-file JSON (see scenario_writer.h). Field names
// and forms are the schema's (scenarios/schema.json); each truth kind
// writes the fields its Map* reader in scenario_loader.cpp reads.
#include "talus/harness/scenario/scenario_writer.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <variant>

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

// The kind and its own fields; `names` turns body indices into names.
ordered_json KindJson(const TruthKind& kind, const std::vector<BodySpec>& bodies) {
  struct Visitor {
    const std::vector<BodySpec>& bodies;
    ordered_json operator()(const FreeFallTruth& t) const {
      ordered_json out = {{"kind", "free_fall"}, {"y0", t.y0}, {"v0", t.v0}, {"g", t.g}};
      if (std::isfinite(t.until)) out["until"] = t.until;
      return out;
    }
    ordered_json operator()(const SlidingStopTruth& t) const {
      return {{"kind", "sliding_stop"},
              {"v0", t.v0},
              {"mu", t.mu},
              {"g", t.g},
              {"direction", Vec(t.direction)},
              {"maxLateral", t.maxLateral}};
    }
    ordered_json operator()(const RestHeightTruth& t) const {
      return {{"kind", "rest_height"}, {"height", t.height}, {"maxJitter", t.maxJitter}};
    }
    ordered_json operator()(const BounceHeightsTruth& t) const {
      return {{"kind", "bounce_heights"}, {"h", t.h}, {"e", t.e}, {"count", t.count}};
    }
    ordered_json operator()(const ConvergedReferenceTruth& t) const {
      return {{"kind", "converged_reference"}, {"timeStepDivisor", t.timeStepDivisor}};
    }
    ordered_json operator()(const StackRestTruth& t) const {
      ordered_json layers = ordered_json::array();
      for (const auto& layer : t.layers) {
        ordered_json names = ordered_json::array();
        for (int body : layer) names.push_back(bodies[static_cast<std::size_t>(body)].name);
        layers.push_back(names);
      }
      return {{"kind", "stack_rest"},
              {"layers", layers},
              {"floor", t.floor},
              {"layerHeight", t.layerHeight},
              {"maxDrift", t.maxDrift}};
    }
    ordered_json operator()(const HullRestTruth& t) const {
      return {{"kind", "hull_rest"},
              {"faceNormal", Vec(t.faceNormal)},
              {"floor", t.floor},
              {"height", t.height},
              {"maxFaceAngle", t.maxFaceAngle}};
    }
    ordered_json operator()(const InclineSlideTruth& t) const {
      return {{"kind", "incline_slide"}, {"angle", t.angle}, {"mu", t.mu}, {"g", t.g}};
    }
    ordered_json operator()(const InclineTipTruth& t) const {
      return {{"kind", "incline_tip"},
              {"angle", t.angle},
              {"mu", t.mu},
              {"width", t.width},
              {"height", t.height},
              {"tiltThreshold", t.tiltThreshold},
              {"maxStayTilt", t.maxStayTilt}};
    }
    ordered_json operator()(const TorqueFreeTruth& t) const {
      return {{"kind", "torque_free"}, {"inertia", Vec(t.inertia)}, {"omega", Vec(t.omega)}};
    }
    ordered_json operator()(const FlipPeriodTruth& t) const {
      return {{"kind", "flip_period"}, {"inertia", Vec(t.inertia)}, {"omega", Vec(t.omega)}};
    }
    ordered_json operator()(const ProjectileTruth& t) const {
      return {{"kind", "projectile"}, {"x0", Vec(t.x0)}, {"v0", Vec(t.v0)}};
    }
    ordered_json operator()(const BoxLandingTruth& t) const {
      return {{"kind", "box_landing"},
              {"floor", t.floor},
              {"restAfter", t.restAfter},
              {"maxFaceAngle", t.maxFaceAngle},
              {"maxMotion", t.maxMotion},
              {"maxEnergyRise", t.maxEnergyRise},
              {"maxPenetration", t.maxPenetration}};
    }
    ordered_json operator()(const EnergyDriftTruth&) const { return {{"kind", "energy_drift"}}; }
    ordered_json operator()(const AngularMomentumDriftTruth& t) const {
      return {{"kind", "angular_momentum_drift"},
              {"metric", t.metric == MomentumMetric::Magnitude ? "magnitude" : "vector"}};
    }
    ordered_json operator()(const RotationalEnergyDriftTruth&) const {
      return {{"kind", "rotational_energy_drift"}};
    }
  };
  return std::visit(Visitor{bodies}, kind);
}

ordered_json TruthJson(const Truth& truth, const std::vector<BodySpec>& bodies) {
  ordered_json out = KindJson(truth.kind, bodies);
  // Secondary bounds are written {"value", "reason"}: KindJson gives the
  // value, the truth keeps the reason.
  for (auto& [name, value] : out.items()) {
    const bool bound =
        std::find(kSecondaryBounds.begin(), kSecondaryBounds.end(), name) != kSecondaryBounds.end();
    if (!value.is_number() || !bound) continue;
    const auto reason = truth.boundReasons.find(name);
    value =
        ordered_json{{"value", value}, {"reason", reason == truth.boundReasons.end() ? "" : reason->second}};
  }
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
