// Replay recording and its JSON form (see replay.h). Frames are picked from
// the trajectory's samples at evenly spaced indices, like the plot series,
// so the first and last samples are always kept. Reading checks every
// field's type and names the place of the first bad one.
#include "talus/harness/run/replay.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <type_traits>

#include "support/text_util.h"
#include "talus/hull_builder.h"

namespace talus::harness {
namespace {

using Json = nlohmann::ordered_json;

Json Vector(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

const char* KindName(ReplayShape::Kind kind) {
  switch (kind) {
    case ReplayShape::Kind::Box:
      return "box";
    case ReplayShape::Kind::Sphere:
      return "sphere";
    case ReplayShape::Kind::Hull:
      return "hull";
  }
  return "box";
}

Json ShapeToJson(const ReplayShape& shape) {
  Json j;
  j["kind"] = KindName(shape.kind);
  j["static"] = shape.isStatic;
  if (shape.kind == ReplayShape::Kind::Box) j["halfExtents"] = Vector(shape.halfExtents);
  if (shape.kind == ReplayShape::Kind::Sphere) j["radius"] = shape.radius;
  if (shape.kind == ReplayShape::Kind::Hull) {
    j["vertices"] = Json::array();
    for (const Vec3& v : shape.vertices) j["vertices"].push_back(Vector(v));
    j["faces"] = shape.faces;
  }
  return j;
}

// Reading: a bad field is reported as "<where>/<key>: expected ...".
struct Reader {
  std::string error;

  bool Fail(const std::string& where, const char* what) {
    if (error.empty()) error = Concat({where, ": expected ", what});
    return false;
  }
  bool Number(const Json& j, const std::string& where, double& out) {
    if (!j.is_number()) return Fail(where, "a number");
    out = j.get<double>();
    return true;
  }
  bool Numbers(const Json& j, std::size_t count, const std::string& where, double* out) {
    if (!j.is_array() || j.size() != count) return Fail(where, "an array of numbers of the right length");
    for (std::size_t i = 0; i < count; ++i) {
      if (!Number(j[i], where, out[i])) return false;
    }
    return true;
  }
  bool Vector(const Json& j, const std::string& where, Vec3& out) {
    double v[3];
    if (!Numbers(j, 3, where, v)) return false;
    out = Vec3(v[0], v[1], v[2]);
    return true;
  }
  const Json* Field(const Json& j, const char* key, const std::string& where) {
    if (!j.is_object() || !j.contains(key)) {
      Fail(Concat({where, "/", key}), "a field");
      return nullptr;
    }
    return &j[key];
  }
};

bool ReadShape(Reader& reader, const Json& j, const std::string& where, ReplayShape& shape) {
  const Json* kind = reader.Field(j, "kind", where);
  const Json* isStatic = reader.Field(j, "static", where);
  if (kind == nullptr || isStatic == nullptr) return false;
  if (!isStatic->is_boolean()) return reader.Fail(where + "/static", "true or false");
  shape.isStatic = isStatic->get<bool>();
  if (*kind == "box") {
    shape.kind = ReplayShape::Kind::Box;
    const Json* half = reader.Field(j, "halfExtents", where);
    return half != nullptr && reader.Vector(*half, where + "/halfExtents", shape.halfExtents);
  }
  if (*kind == "sphere") {
    shape.kind = ReplayShape::Kind::Sphere;
    const Json* radius = reader.Field(j, "radius", where);
    return radius != nullptr && reader.Number(*radius, where + "/radius", shape.radius);
  }
  if (*kind != "hull") return reader.Fail(where + "/kind", "\"box\", \"sphere\" or \"hull\"");
  shape.kind = ReplayShape::Kind::Hull;
  const Json* vertices = reader.Field(j, "vertices", where);
  const Json* faces = reader.Field(j, "faces", where);
  if (vertices == nullptr || faces == nullptr) return false;
  if (!vertices->is_array()) return reader.Fail(where + "/vertices", "an array");
  for (const Json& v : *vertices) {
    if (!reader.Vector(v, where + "/vertices", shape.vertices.emplace_back())) return false;
  }
  if (!faces->is_array()) return reader.Fail(where + "/faces", "an array");
  for (const Json& face : *faces) {
    auto& loop = shape.faces.emplace_back();
    if (!face.is_array()) return reader.Fail(where + "/faces", "arrays of vertex indices");
    for (const Json& index : face) {
      if (!index.is_number_integer() || index.get<int>() < 0 ||
          index.get<std::size_t>() >= shape.vertices.size()) {
        return reader.Fail(where + "/faces", "vertex indices in range");
      }
      loop.push_back(index.get<int>());
    }
  }
  return true;
}

bool ReadFrame(Reader& reader, const Json& j, const std::string& where, std::size_t bodies,
               std::size_t counters, ReplayFrame& frame) {
  const Json* t = reader.Field(j, "t", where);
  const Json* p = reader.Field(j, "p", where);
  const Json* q = reader.Field(j, "q", where);
  const Json* c = reader.Field(j, "c", where);
  const Json* n = reader.Field(j, "n", where);
  if (t == nullptr || p == nullptr || q == nullptr || c == nullptr || n == nullptr) return false;
  if (!reader.Number(*t, where + "/t", frame.time)) return false;
  if (!p->is_array() || p->size() != bodies) return reader.Fail(where + "/p", "one position per body");
  if (!q->is_array() || q->size() != bodies) return reader.Fail(where + "/q", "one orientation per body");
  for (std::size_t b = 0; b < bodies; ++b) {
    if (!reader.Vector((*p)[b], where + "/p", frame.positions.emplace_back())) return false;
    double w[4];
    if (!reader.Numbers((*q)[b], 4, where + "/q", w)) return false;
    frame.orientations.emplace_back(w[0], w[1], w[2], w[3]);
  }
  if (!c->is_array()) return reader.Fail(where + "/c", "an array");
  for (const Json& contact : *c) {
    double v[9];
    if (!reader.Numbers(contact, 9, where + "/c", v)) return false;
    const auto inRange = [&](double index) { return index >= 0.0 && index < static_cast<double>(bodies); };
    if (!inRange(v[0]) || !inRange(v[1])) return reader.Fail(where + "/c", "body indices in range");
    frame.contacts.push_back({static_cast<int>(v[0]), static_cast<int>(v[1]), Vec3(v[2], v[3], v[4]),
                              Vec3(v[5], v[6], v[7]), v[8]});
  }
  if (!n->is_array() || (!n->empty() && n->size() != counters)) {
    return reader.Fail(where + "/n", "one value per counter");
  }
  for (const Json& value : *n) {
    if (!reader.Number(value, where + "/n", frame.counters.emplace_back())) return false;
  }
  return true;
}

}  // namespace

Result<ReplayShape> MakeReplayShape(const BodySpec& body) {
  ReplayShape shape;
  shape.isStatic = body.motion == Motion::Static;
  if (const auto* box = std::get_if<BoxShape>(&body.shape)) {
    shape.kind = ReplayShape::Kind::Box;
    shape.halfExtents = box->halfExtents;
  } else if (const auto* sphere = std::get_if<SphereShape>(&body.shape)) {
    shape.kind = ReplayShape::Kind::Sphere;
    shape.radius = sphere->radius;
  } else {
    const auto& points = std::get<HullShape>(body.shape).points;
    auto hull = BuildHull(points);
    if (!hull) return Error{Concat({"body \"", body.name, "\": ", hull.GetError().message})};
    shape.kind = ReplayShape::Kind::Hull;
    const auto vertices = hull.Value().Vertices();
    shape.vertices.assign(vertices.begin(), vertices.end());
    for (int f = 0; f < hull.Value().FaceCount(); ++f) shape.faces.push_back(hull.Value().FaceVertices(f));
  }
  return shape;
}

Result<Replay> MakeReplay(const Run& run, const Trajectory& trajectory, int maxFrames) {
  assert(maxFrames >= 2);
  Replay replay;
  for (const BodySpec& body : run.scenario.bodies) {
    auto shape = MakeReplayShape(body);
    if (!shape) return shape.GetError();
    replay.shapes.push_back(std::move(shape).Value());
  }
  const std::size_t count = trajectory.samples.size();
  if (count == 0) return replay;
  for (const StepCounter& counter : trajectory.samples.back().counters)
    replay.counterNames.push_back(counter.name);
  for (const std::size_t index : SpreadIndices(count, static_cast<std::size_t>(maxFrames))) {
    const Sample& sample = trajectory.samples[index];
    ReplayFrame frame;
    frame.time = sample.time;
    for (const BodyReading& state : sample.bodies) {
      frame.positions.push_back(state.origin);
      frame.orientations.push_back(state.orientation);
    }
    frame.contacts = sample.contacts;
    // Counters by name, so a backend that changed its list mid-run cannot misalign them.
    if (!sample.counters.empty()) {
      for (const std::string& name : replay.counterNames) {
        const auto it = std::find_if(sample.counters.begin(), sample.counters.end(),
                                     [&](const StepCounter& c) { return c.name == name; });
        frame.counters.push_back(it == sample.counters.end() ? 0.0 : it->value);
      }
    }
    replay.frames.push_back(std::move(frame));
  }
  return replay;
}

bool IsReplaySelected(const Run& run, const std::vector<std::string>& selection) {
  return std::any_of(selection.begin(), selection.end(), [&](const std::string& entry) {
    return entry == "all" || entry == run.id || entry == run.scenario.name;
  });
}

Json ReplayToJson(const Replay& replay) {
  Json j;
  j["shapes"] = Json::array();
  for (const ReplayShape& shape : replay.shapes) j["shapes"].push_back(ShapeToJson(shape));
  j["counters"] = replay.counterNames;
  j["frames"] = Json::array();
  for (const ReplayFrame& frame : replay.frames) {
    Json f;
    f["t"] = frame.time;
    f["p"] = Json::array();
    for (const Vec3& p : frame.positions) f["p"].push_back(Vector(p));
    f["q"] = Json::array();
    for (const Quat& q : frame.orientations) f["q"].push_back(Json::array({q.w(), q.x(), q.y(), q.z()}));
    f["c"] = Json::array();
    for (const ContactReading& c : frame.contacts) {
      f["c"].push_back(Json::array({c.bodyA, c.bodyB, c.point.x(), c.point.y(), c.point.z(), c.normal.x(),
                                    c.normal.y(), c.normal.z(), c.depth}));
    }
    f["n"] = frame.counters;
    j["frames"].push_back(std::move(f));
  }
  return j;
}

Result<Replay> ReplayFromJson(const Json& json, const std::string& where) {
  Reader reader;
  Replay replay;
  const Json* shapes = reader.Field(json, "shapes", where);
  const Json* counters = reader.Field(json, "counters", where);
  const Json* frames = reader.Field(json, "frames", where);
  if (shapes == nullptr || counters == nullptr || frames == nullptr) return Error{reader.error};
  if (!shapes->is_array()) return Error{Concat({where, "/shapes: expected an array"})};
  for (std::size_t i = 0; i < shapes->size(); ++i) {
    if (!ReadShape(reader, (*shapes)[i], Concat({where, "/shapes/", std::to_string(i)}),
                   replay.shapes.emplace_back())) {
      return Error{reader.error};
    }
  }
  if (!counters->is_array()) return Error{Concat({where, "/counters: expected an array"})};
  for (const Json& name : *counters) {
    if (!name.is_string()) return Error{Concat({where, "/counters: expected strings"})};
    replay.counterNames.push_back(name.get<std::string>());
  }
  if (!frames->is_array()) return Error{Concat({where, "/frames: expected an array"})};
  for (std::size_t i = 0; i < frames->size(); ++i) {
    if (!ReadFrame(reader, (*frames)[i], Concat({where, "/frames/", std::to_string(i)}), replay.shapes.size(),
                   replay.counterNames.size(), replay.frames.emplace_back())) {
      return Error{reader.error};
    }
  }
  return replay;
}

}  // namespace talus::harness
