// A scenario file's "loads" and "impulses" to the scenario model
// (applied_loads_mapping.h).
#include "scenario/applied_loads_mapping.h"

#include <cmath>
#include <optional>
#include <string>

#include "scenario/scenario_mapping_support.h"
#include "support/text_util.h"
#include "talus/harness/scenario/scenario_limits.h"

namespace talus::harness {
namespace {

using nlohmann::json;

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

// The point of application "at" of the entry at `pointer`, refused beyond
// the coordinate limit (scenario_limits.h).
Result<Vec3> MapPointOfApplication(const json& entry, std::string_view file, const std::string& pointer) {
  const Vec3 point = ReadVec3(entry["at"]);
  if (const double far = point.cwiseAbs().maxCoeff(); far > kMaxLength) {
    return FieldError(file, pointer + "/at",
                      Concat({"coordinate ", FormatNumber(far), " m is beyond the limit of ",
                              FormatNumber(kMaxLength), " m"}));
  }
  return point;
}

// The load's window ("start", "end") must act inside the run, which ends at
// `runEnd` seconds.
std::optional<Error> CheckLoadWindow(const json& entry, const AppliedLoad& load, double runEnd,
                                     std::string_view file, const std::string& pointer) {
  // Within round-off of the run's end counts as the end: a duration in
  // seconds is rounded to whole steps.
  const double slack = 1e-9 * runEnd;
  if (load.start >= runEnd - slack) {
    return FieldError(file, pointer + "/start",
                      Concat({"starts at ", FormatNumber(load.start), " s, not before the run ends at ",
                              FormatNumber(runEnd), " s: it would never act"}));
  }
  if (!entry.contains("end")) return std::nullopt;
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
  return std::nullopt;
}

// One entry of "loads" at `pointer`, the run ending at `runEnd` seconds.
Result<AppliedLoad> MapLoad(const json& entry, const std::vector<BodySpec>& bodies, const BodyIndex& names,
                            double runEnd, std::string_view file, const std::string& pointer) {
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
    auto point = MapPointOfApplication(entry, file, pointer);
    if (!point) return point.GetError();
    load.point = point.Value();
  }
  if (entry.contains("start")) load.start = entry["start"].get<double>();
  if (entry.contains("end")) load.end = entry["end"].get<double>();
  if (auto problem = CheckLoadWindow(entry, load, runEnd, file, pointer)) return *problem;
  return load;
}

}  // namespace

Result<std::vector<AppliedLoad>> MapLoads(const json& doc, const std::vector<BodySpec>& bodies,
                                          const BodyIndex& names, const WorldSpec& world,
                                          std::string_view file) {
  std::vector<AppliedLoad> loads;
  if (!doc.contains("loads")) return loads;
  const double runEnd = RunSeconds(world);
  for (size_t i = 0; i < doc["loads"].size(); ++i) {
    auto load = MapLoad(doc["loads"][i], bodies, names, runEnd, file, "/loads/" + std::to_string(i));
    if (!load) return load.GetError();
    loads.push_back(load.Value());
  }
  return loads;
}

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
      auto point = MapPointOfApplication(entry, file, pointer);
      if (!point) return point.GetError();
      impulse.point = point.Value();
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

}  // namespace talus::harness
