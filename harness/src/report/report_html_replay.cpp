// The report's replay and figure sections (see report_html_replay.h).
//
// Data for the page, as JSON in a <script type="application/json"> element:
//   runs       per run recorded for replay: its id, the body shapes (same
//              for every backend), and per backend the frames (poses,
//              contacts, step counters) as results.json holds them;
//   hullTrace  a Quickhull build traced step by step (talus/
//              hull_build_trace.h) on a fixed point cloud: the points, every
//              step (faces as point loops, which the eye sees, the horizon)
//              and the finished hull's faces as loops of input indices.
// The demo cloud is fixed (SplitMix64 seed below), so the page is
// deterministic. The scripts come from harness/report/src (report_assets.h).
#include "report/report_html_replay.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "report/report_assets.h"
#include "support/text_util.h"
#include "talus/harness/support/split_mix64.h"
#include "talus/hull_builder.h"

namespace talus::harness {
namespace {

using Json = nlohmann::ordered_json;

// The figure-1 point cloud: kTracePoints points, most near the unit sphere
// (so most become vertices and the hull grows visibly) and a quarter
// inside it (to show points that are dropped). 40 keeps the page small and
// the steps countable.
constexpr int kTracePoints = 40;
constexpr std::uint64_t kTraceSeed = 0x5EED0F16;

std::vector<Vec3> TracePoints() {
  SplitMix64 random(kTraceSeed);
  std::vector<Vec3> points;
  while (static_cast<int>(points.size()) < kTracePoints) {
    const Vec3 p(2.0 * random.NextUniform() - 1.0, 2.0 * random.NextUniform() - 1.0,
                 2.0 * random.NextUniform() - 1.0);
    const double length = p.norm();
    if (length < 0.1 || length > 1.0) continue;  // uniform directions from the ball
    const double radius = points.size() % 4 == 3 ? 0.5 * length : 0.8 + 0.2 * random.NextUniform();
    points.push_back(p / length * radius);
  }
  return points;
}

Json HullTraceJson() {
  const std::vector<Vec3> points = TracePoints();
  HullBuildTrace trace;
  auto hull = BuildHull(points, {.trace = &trace});
  Json j;
  j["points"] = Json::array();
  for (const Vec3& p : points) j["points"].push_back({p.x(), p.y(), p.z()});
  j["steps"] = Json::array();
  for (const HullBuildTraceStep& step : trace.steps) {
    Json s;
    s["faces"] = step.faces;
    s["visible"] = step.visible;
    s["eye"] = step.eye;
    s["horizon"] = step.horizon;
    j["steps"].push_back(std::move(s));
  }
  // Hull vertices are input points bit for bit: map them back to indices.
  j["finalFaces"] = Json::array();
  if (hull) {
    const auto vertices = hull.Value().Vertices();
    std::vector<int> inputIndex(vertices.size(), 0);
    for (std::size_t v = 0; v < vertices.size(); ++v) {
      for (std::size_t i = 0; i < points.size(); ++i) {
        if (points[i] == vertices[v]) inputIndex[v] = static_cast<int>(i);
      }
    }
    for (int f = 0; f < hull.Value().FaceCount(); ++f) {
      Json loop = Json::array();
      for (int v : hull.Value().FaceVertices(f)) loop.push_back(inputIndex[static_cast<std::size_t>(v)]);
      j["finalFaces"].push_back(std::move(loop));
    }
  }
  return j;
}

Json ReplayRunsJson(const ResultsFile& file) {
  Json runs = Json::array();
  for (const RunResult& r : file.results) {
    if (r.replay.frames.empty()) continue;
    if (runs.empty() || runs.back()["id"] != r.runId) {
      const Json replay = ReplayToJson(r.replay);
      runs.push_back({{"id", r.runId},
                      {"bodies", r.bodyNames},
                      {"shapes", replay["shapes"]},
                      {"results", Json::array()}});
    }
    const Json replay = ReplayToJson(r.replay);
    runs.back()["results"].push_back(
        {{"backend", r.backend}, {"counters", replay["counters"]}, {"frames", replay["frames"]}});
  }
  return runs;
}

constexpr const char* kStyle =
    R"(.replay-controls{display:flex;gap:1em;align-items:center;margin:.5em 0}.replay-controls input[type=range]{width:30em}
.replay-stage{position:relative}.replay-label{position:absolute;background:#fffc;padding:0 .4em;font-size:90%}
#report-status{font-size:80%;color:#777;white-space:pre-wrap})";

}  // namespace

std::string ReplaySections(const ResultsFile& file, std::string_view threeLibrary) {
  Json data;
  data["runs"] = ReplayRunsJson(file);
  data["hullTrace"] = HullTraceJson();
  std::ostringstream out;
  out << "<style>" << kStyle << "</style>\n";
  out << "<h2>Replay</h2>\n<p>Every run recorded with <code>talus-testbed run --replay</code>, one view per "
         "engine; drag to orbit, wheel to zoom. Contact points in red, normals (from B towards A) as red "
         "lines.</p>\n<div id=\"replay\"></div>\n";
  out << "<h2>Quickhull step by step</h2>\n<p>The original write-up's figure 1 on a fixed cloud of "
      << kTracePoints
      << " points: the current hull (blue), the eye point (yellow), the faces it sees (red), the horizon "
         "(orange) and the new cone (green).</p>\n<div id=\"hull-trace\"></div>\n";
  out << "<h2>Broad phase per step</h2>\n<p>The original write-up's figure 2 for each replayed run: bodies, "
         "candidate pairs met by the broad-phase structure, pairs whose bounding spheres touch, SAT tests, "
         "intersecting pairs and contact points, per step, from the engine's step statistics.</p>\n"
         "<div class=\"plots\" id=\"broadphase\"></div>\n";
  out << "<pre id=\"report-status\"></pre>\n";
  out << "<script>" << ScriptSafe(kReportStatusScript) << "</script>\n";
  out << "<script type=\"application/json\" id=\"replay-data\">" << ScriptSafe(data.dump()) << "</script>\n";
  if (!threeLibrary.empty()) out << "<script>\n" << ScriptSafe(std::string(threeLibrary)) << "\n</script>\n";
  out << "<script>" << ScriptSafe(kReportReplayScript) << "</script>\n";
  return out.str();
}

}  // namespace talus::harness
