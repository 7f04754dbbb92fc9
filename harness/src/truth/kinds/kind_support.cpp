// The reading checks more than one truth kind makes (kind_support.h).
#include "truth/kinds/kind_support.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "support/text_util.h"
#include "talus/harness/support/number_text.h"

namespace talus::harness {

std::optional<Error> RefuseStaticBodies(const TruthReader& reader, const std::string& kind) {
  for (const BodySpec& body : reader.bodies) {
    if (body.motion == Motion::Static) {
      return reader.Refuse("/kind",
                           kind + " is a free-body truth, but body " + Quoted(body.name) + " is static");
    }
  }
  return std::nullopt;
}

std::optional<Error> RefuseStillStart(const TruthReader& reader, const std::string& kind, bool spin) {
  if (auto refused = RefuseStaticBodies(reader, kind)) return refused;
  bool moving = false;
  for (size_t b = 0; b < reader.bodies.size(); ++b) {
    if (reader.body >= 0 && b != static_cast<size_t>(reader.body)) continue;
    const BodySpec& body = reader.bodies[b];
    if (body.motion != Motion::Dynamic) continue;
    moving = moving || body.angularVelocity.norm() > 0.0 || (!spin && body.linearVelocity.norm() > 0.0);
  }
  if (moving) return std::nullopt;
  return reader.Refuse(reader.body >= 0 ? "/body" : "/kind",
                       kind + (spin ? " needs a dynamic body that starts spinning (a relative drift of 0)"
                                    : " needs a dynamic body that starts moving (a relative drift of 0)"));
}

// Torque-free truths are written in the body's principal frame, so they
// need a box body, whose own frame is principal: the moments must be in the
// box's proportions and omega must be the file's world angular velocity
// seen from the body.
Result<SpinStart> ReadSpinStart(const TruthReader& reader) {
  const Vec3 inertia = reader.Vector("inertia");
  const Vec3 omega = reader.Vector("omega");
  const BodySpec& body = reader.bodies[reader.body];
  const auto* box = std::get_if<BoxShape>(&body.shape);
  if (box == nullptr || body.motion != Motion::Dynamic) {
    return reader.Refuse("/body", "a spin truth needs a dynamic box body (its frame is principal)");
  }
  const Vec3 e = box->halfExtents.cwiseProduct(box->halfExtents);
  const Vec3 shape(e.y() + e.z(), e.x() + e.z(), e.x() + e.y());
  const Vec3 scaled = shape * (inertia.sum() / shape.sum());
  if ((scaled - inertia).norm() > kSpinConsistencyTolerance * inertia.norm()) {
    std::ostringstream problem;
    problem << "is not in the proportions of the box's principal moments (" << shape.x() << " : " << shape.y()
            << " : " << shape.z() << ")";
    return reader.Refuse("/inertia", problem.str());
  }
  const Vec3 bodyOmega = body.orientation.conjugate() * body.angularVelocity;
  if ((bodyOmega - omega).norm() > kSpinConsistencyTolerance * (1.0 + omega.norm())) {
    return reader.Refuse("/omega", "differs from the body's angularVelocity seen in its own frame");
  }
  return SpinStart{inertia, omega};
}

Result<std::vector<int>> ReadDynamicBodies(const TruthReader& reader, const char* field) {
  std::vector<int> bodies;
  if (!reader.Has(field)) {
    for (std::size_t b = 0; b < reader.bodies.size(); ++b) {
      if (reader.bodies[b].motion == Motion::Dynamic) bodies.push_back(static_cast<int>(b));
    }
    return bodies;
  }
  const nlohmann::json& names = reader.entry[field];
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string where = Concat({"/", field, "/", std::to_string(i)});
    const std::string name = names[i].get<std::string>();
    const int body = reader.FindBody(name);
    if (body < 0) return reader.Refuse(where, "no body named " + Quoted(name));
    if (std::find(bodies.begin(), bodies.end(), body) != bodies.end()) {
      return reader.Refuse(where, "body " + Quoted(name) + " is listed twice");
    }
    if (reader.bodies[body].motion != Motion::Dynamic) {
      return reader.Refuse(where, "body " + Quoted(name) + " is static");
    }
    bodies.push_back(body);
  }
  return bodies;
}

Result<TimeWindow> ReadTimeWindow(const TruthReader& reader, const char* fromField, const char* untilField) {
  const double duration = reader.Duration();
  TimeWindow window{0.0, duration};
  if (fromField != nullptr && reader.Has(fromField)) window.from = reader.Number(fromField);
  if (untilField != nullptr && reader.Has(untilField)) window.until = reader.Number(untilField);
  const std::string end = Concat({"the run ends at ", FormatNumber(duration), " s"});
  // Each refusal below names a field that was read: a default end is the
  // run's own, a default start 0, which is before any end (> 0).
  if (window.until > duration) {
    return reader.Refuse(Concat({"/", untilField}),
                         Concat({FormatNumber(window.until), " s is after the end of the run (", end, ")"}));
  }
  if (window.from >= duration) {
    return reader.Refuse(
        Concat({"/", fromField}),
        Concat({FormatNumber(window.from), " s is not before the end of the run (", end, ")"}));
  }
  if (window.from >= window.until) {
    return reader.Refuse(Concat({"/", fromField}),
                         Concat({FormatNumber(window.from), " s is not before \"", untilField, "\" (",
                                 FormatNumber(window.until), " s): the window is empty"}));
  }
  return window;
}

std::optional<Error> RequireAbsoluteTolerance(const TruthReader& reader, std::string_view unit) {
  if (reader.entry["tolerance"].value("absolute", 0.0) > 0.0) return std::nullopt;
  return reader.Refuse(
      "/tolerance/absolute",
      Concat({"is required (", unit, "): the truth is 0, so a relative tolerance alone allows nothing"}));
}

double RotationAngle(const Quat& a, const Quat& b) {
  // The relative rotation's half angle from its sine and cosine: accurate
  // for small angles too (acos of |<a, b>| loses half the digits there),
  // and q and -q give the same angle.
  const Quat d = a.normalized().conjugate() * b.normalized();
  return 2.0 * std::atan2(d.vec().norm(), std::abs(d.w()));
}

}  // namespace talus::harness
