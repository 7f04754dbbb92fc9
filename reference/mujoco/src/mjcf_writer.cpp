// A scenario run as MJCF text (see mjcf_writer.h).
#include "mjcf_writer.h"

#include <charconv>
#include <cmath>
#include <string_view>
#include <vector>

#include "talus/reference/mujoco_backend.h"

namespace talus::reference {
namespace {

using harness::BodySpec;
using harness::Run;

// Shortest text that reads back as the same double.
std::string Num(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

std::string Vec(const Vec3& v) { return Num(v.x()) + " " + Num(v.y()) + " " + Num(v.z()); }

// MJCF quaternions are w x y z.
std::string QuatText(const Quat& q) {
  return Num(q.w()) + " " + Num(q.x()) + " " + Num(q.y()) + " " + Num(q.z());
}

// A pair's contact material as MuJoCo gets it.
struct PairMaterial {
  double friction = 0.0;
  MujocoSolref solref;
};

bool SameSolref(const MujocoSolref& a, const MujocoSolref& b) {
  return a.first == b.first && a.second == b.second;
}

// The friction, torsional and rolling coefficients of a geom or pair: the
// torsional and rolling values are MuJoCo's defaults, unused with condim 3.
std::string FrictionText(double mu, bool pair) {
  return pair ? Num(mu) + " " + Num(mu) + " 0.005 0.0001 0.0001" : Num(mu) + " 0.005 0.0001";
}

std::string SolrefAttribute(const MujocoSolref& solref) {
  const MujocoSolref defaults;
  if (SameSolref(solref, defaults)) return {};
  return " solref=\"" + Num(solref.first) + " " + Num(solref.second) + "\"";
}

// What the scenario asks for the pair (a, b).
PairMaterial Wanted(const Run& run, const BodySpec& a, const BodySpec& b) {
  const auto& world = run.scenario.world;
  const double e = harness::Combine(world.restitutionCombine, a.restitution, b.restitution);
  return {harness::Combine(world.frictionCombine, a.friction, b.friction),
          MujocoSolrefForRestitution(e, run.timeStep)};
}

// What MuJoCo's own mixing gives from the two geoms (equal priority):
// friction by the maximum; solref by the solmix-weighted average (default
// solmix 1 each, so the plain mean).
PairMaterial Mixed(const Run& run, const BodySpec& a, const BodySpec& b) {
  const MujocoSolref sa = MujocoSolrefForRestitution(a.restitution, run.timeStep);
  const MujocoSolref sb = MujocoSolrefForRestitution(b.restitution, run.timeStep);
  return {std::max(a.friction, b.friction), {0.5 * (sa.first + sb.first), 0.5 * (sa.second + sb.second)}};
}

void WriteOptions(const Run& run, const MujocoProfile& profile, std::string& out) {
  out += "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n";
  out +=
      "  <option timestep=\"" + Num(run.timeStep) + "\" gravity=\"" + Vec(run.scenario.world.gravity) + "\"";
  if (run.iterations > 0) out += " iterations=\"" + std::to_string(run.iterations) + "\"";
  const bool contactFree = run.scenario.bodies.size() == 1;
  const std::string& integrator = contactFree && !profile.contactFreeIntegrator.empty()
                                      ? profile.contactFreeIntegrator
                                      : profile.integrator;
  if (!integrator.empty()) out += " integrator=\"" + integrator + "\"";
  if (!profile.cone.empty()) out += " cone=\"" + profile.cone + "\"";
  if (profile.noslipIterations > 0)
    out += " noslip_iterations=\"" + std::to_string(profile.noslipIterations) + "\"";
  if (profile.impratio > 0.0) out += " impratio=\"" + Num(profile.impratio) + "\"";
  if (profile.tolerance > 0.0) out += " tolerance=\"" + Num(profile.tolerance) + "\"";
  if (profile.multiccd) {
    out += ">\n    <flag multiccd=\"enable\"/>\n  </option>\n";
  } else {
    out += "/>\n";
  }
}

void WriteBody(const BodySpec& spec, const BodyMass& mass, int index, const Run& run, std::string& out) {
  const std::string id = std::to_string(index);
  const bool dynamic = spec.motion == harness::Motion::Dynamic;
  // Geom placement inside the MJCF body (see the header).
  Vec3 geomPosition = Vec3::Zero();
  Quat geomOrientation = Quat::Identity();
  if (dynamic) {
    const Vec3 com = spec.position + spec.orientation.toRotationMatrix() * mass.centroid;
    const Quat comOrientation = (spec.orientation * mass.principalRotation).normalized();
    out += "    <body name=\"b" + id + "\" pos=\"" + Vec(com) + "\" quat=\"" + QuatText(comOrientation) +
           "\">\n";
    out += "      <freejoint/>\n";
    out += "      <inertial pos=\"0 0 0\" mass=\"" + Num(mass.mass) + "\" diaginertia=\"" +
           Vec(mass.principalInertia) + "\"/>\n";
    geomOrientation = mass.principalRotation.conjugate();
    geomPosition = -(geomOrientation * mass.centroid);
  } else {
    // A kinematic body is a mocap body at the scenario frame, moved by the
    // backend each step (mujoco_backend.cpp); a static one a fixed body.
    const bool mocap = spec.motion == harness::Motion::Kinematic;
    out += "    <body name=\"b" + id + "\"" + (mocap ? " mocap=\"true\"" : "") + " pos=\"" +
           Vec(spec.position) + "\" quat=\"" + QuatText(spec.orientation) + "\">\n";
  }
  out += "      <geom name=\"g" + id + "\"";
  if (const auto* box = std::get_if<harness::BoxShape>(&spec.shape)) {
    out += " type=\"box\" size=\"" + Vec(box->halfExtents) + "\"";
  } else if (const auto* sphere = std::get_if<harness::SphereShape>(&spec.shape)) {
    out += " type=\"sphere\" size=\"" + Num(sphere->radius) + "\"";
  } else {
    out += " type=\"mesh\" mesh=\"m" + id + "\"";
  }
  out += " pos=\"" + Vec(geomPosition) + "\" quat=\"" + QuatText(geomOrientation) + "\"";
  out += " friction=\"" + FrictionText(spec.friction, false) + "\"";
  out += SolrefAttribute(MujocoSolrefForRestitution(spec.restitution, run.timeStep));
  out += "/>\n    </body>\n";
}

}  // namespace

Result<MjcfModel> WriteMjcf(const Run& run, std::span<const BodyMass> masses, const MujocoProfile& profile) {
  const auto& bodies = run.scenario.bodies;
  // The pairs whose material MuJoCo's mixing would get wrong, found first so
  // that a world needing too many is refused before any text is written.
  struct Override {
    int a = 0, b = 0;
    PairMaterial material;
  };
  std::vector<Override> overrides;
  for (size_t a = 0; a < bodies.size(); ++a) {
    for (size_t b = a + 1; b < bodies.size(); ++b) {
      const bool dynamic =
          bodies[a].motion == harness::Motion::Dynamic || bodies[b].motion == harness::Motion::Dynamic;
      if (!dynamic) continue;  // two fixed bodies never collide
      const PairMaterial wanted = Wanted(run, bodies[a], bodies[b]);
      const PairMaterial mixed = Mixed(run, bodies[a], bodies[b]);
      if (wanted.friction == mixed.friction && SameSolref(wanted.solref, mixed.solref)) continue;
      if (overrides.size() >= static_cast<size_t>(kMujocoMaxExplicitPairs)) {
        return Error{"mujoco: the scenario's combine rules (friction " +
                     std::string(harness::CombineRuleName(run.scenario.world.frictionCombine)) +
                     ", restitution " + harness::CombineRuleName(run.scenario.world.restitutionCombine) +
                     ") differ from MuJoCo's mixing for more than " +
                     std::to_string(kMujocoMaxExplicitPairs) +
                     " body pairs; each would need an explicit <pair>"};
      }
      overrides.push_back({static_cast<int>(a), static_cast<int>(b), wanted});
    }
  }

  MjcfModel model;
  model.explicitPairs = static_cast<int>(overrides.size());
  int dynamicBodies = 0;
  for (const BodySpec& body : bodies) dynamicBodies += body.motion == harness::Motion::Dynamic ? 1 : 0;
  model.nconmax = kMujocoBaseContacts + kMujocoContactsPerBody * dynamicBodies;
  // Rows per contact of condim 3: 4 pyramid edges, or 3 for an elliptic cone.
  model.njmax = (profile.cone == "elliptic" ? 3 : 4) * model.nconmax;

  std::string& out = model.text;
  out += "<mujoco model=\"talus-scenario\">\n";
  WriteOptions(run, profile, out);
  out += "  <size nconmax=\"" + std::to_string(model.nconmax) + "\" njmax=\"" + std::to_string(model.njmax) +
         "\"/>\n";
  bool anyHull = false;
  for (const BodySpec& body : bodies)
    anyHull = anyHull || std::holds_alternative<harness::HullShape>(body.shape);
  if (anyHull) {
    out += "  <asset>\n";
    for (size_t i = 0; i < bodies.size(); ++i) {
      const auto* hull = std::get_if<harness::HullShape>(&bodies[i].shape);
      if (hull == nullptr) continue;
      out += "    <mesh name=\"m" + std::to_string(i) + "\" vertex=\"";
      for (size_t p = 0; p < hull->points.size(); ++p) {
        if (p > 0) out += ' ';
        out += Vec(hull->points[p]);
      }
      out += "\"/>\n";
    }
    out += "  </asset>\n";
  }
  out += "  <worldbody>\n";
  for (size_t i = 0; i < bodies.size(); ++i) WriteBody(bodies[i], masses[i], static_cast<int>(i), run, out);
  out += "  </worldbody>\n";
  if (!overrides.empty()) {
    out += "  <contact>\n";
    for (const Override& o : overrides) {
      const std::string a = std::to_string(o.a), b = std::to_string(o.b);
      out += "    <exclude body1=\"b" + a + "\" body2=\"b" + b + "\"/>\n";
      out += "    <pair geom1=\"g" + a + "\" geom2=\"g" + b + "\" condim=\"3\" friction=\"" +
             FrictionText(o.material.friction, true) + "\" solref=\"" + Num(o.material.solref.first) + " " +
             Num(o.material.solref.second) + "\"/>\n";
    }
    out += "  </contact>\n";
  }
  out += "</mujoco>\n";
  return model;
}

}  // namespace talus::reference
