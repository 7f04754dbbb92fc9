// The report's replay and figure sections (see report_html_replay.h).
//
// Data for the page:
//   runs       (in kReportReplayFile beside the page, a script setting
//              window.talusReportReplays) per run recorded for replay: its id,
//              the body shapes (same for every backend), and per backend
//              the frames (poses, contacts, step counters) in the display
//              form (display_trajectory.h's DisplayReplay). They are most of a
//              report's bytes, so the page itself stays small;
//   hullTrace  (as JSON in a <script type="application/json"> element)
//              a Quickhull build traced step by step (talus/
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
#include "talus/harness/run/display_trajectory.h"
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
    const Json replay = ReplayToJson(file.trajectoriesInDisplayForm ? r.replay : DisplayReplay(r.replay));
    runs.back()["results"].push_back(
        {{"backend", r.backend}, {"counters", replay["counters"]}, {"frames", replay["frames"]}});
  }
  return runs;
}

constexpr const char* kReplayStyle =
    R"(.replay-controls{display:flex;gap:1em;align-items:center;margin:.5em 0}.replay-controls input[type=range]{width:30em}
.replay-stage{position:relative}.replay-label{position:absolute;background:#fffc;padding:0 .4em;font-size:90%}
#report-status{font-size:80%;color:#777;white-space:pre-wrap})";

// One row per replayed run and backend that reports its structure: the
// figure-2 scene's answer to "which structure met these pairs".
std::string StructureTable(const ResultsFile& file) {
  std::ostringstream rows;
  for (const RunResult& r : file.results) {
    const std::string ran = StructureThatRan(r.replay);
    if (ran.empty()) continue;
    std::string selected = "-";
    for (const Setting& setting : r.settings) {
      if (setting.key == "broad phase") selected = setting.value;
    }
    rows << "<tr><td>" << EscapeHtml(r.runId) << "</td><td>" << EscapeHtml(r.backend) << "</td><td>"
         << EscapeHtml(selected) << "</td><td>" << EscapeHtml(ran) << "</td></tr>\n";
  }
  if (rows.str().empty()) return {};
  return "<table id=\"broadphase-structure\">\n<tr><th>run</th><th>engine</th><th>broad phase setting</th>"
         "<th>structure that ran</th></tr>\n" +
         rows.str() + "</table>\n";
}

}  // namespace

std::string StructureThatRan(const Replay& replay) {
  const std::string prefix = kStructureCounterPrefix;
  std::vector<std::pair<std::string, int>> steps;  // structure, recorded steps it ran
  std::vector<std::size_t> columns;
  for (std::size_t k = 0; k < replay.counterNames.size(); ++k) {
    if (replay.counterNames[k].rfind(prefix, 0) != 0) continue;
    steps.emplace_back(replay.counterNames[k].substr(prefix.size()), 0);
    columns.push_back(k);
  }
  if (columns.empty()) return {};
  int recorded = 0;
  for (const ReplayFrame& frame : replay.frames) {
    if (frame.counters.size() != replay.counterNames.size()) continue;  // step 0: no step yet
    ++recorded;
    for (std::size_t c = 0; c < columns.size(); ++c)
      steps[c].second += frame.counters[columns[c]] > 0.5 ? 1 : 0;
  }
  std::string text;
  for (const auto& [name, count] : steps) {
    if (count == 0) continue;
    if (count == recorded) return Concat({name, " in all ", std::to_string(recorded), " recorded steps"});
    text += Concat({text.empty() ? "" : ", ", name, " in ", std::to_string(count)});
  }
  if (text.empty()) return {};
  return Concat({text, " of ", std::to_string(recorded), " recorded steps"});
}

std::string ReplaySections(const ResultsFile& file, std::string_view threeLibrary) {
  Json data;
  data["hullTrace"] = HullTraceJson();
  std::ostringstream out;
  out << "<style>" << kReplayStyle << "</style>\n";
  out << "<h2>Replay</h2>\n<p>Every run recorded with <code>talus-testbed run --replay</code>, one view per "
         "engine; drag to orbit, wheel to zoom. Contact points in red, normals (from B towards A) as red "
         "lines.</p>\n<div id=\"replay\"></div>\n";
  out << "<h2>Quickhull step by step</h2>\n<p>The original write-up's figure 1 on a fixed cloud of "
      << kTracePoints
      << " points: the current hull (blue), the eye point (yellow), the faces it sees (red), the horizon "
         "(orange) and the new cone (green).</p>\n<div id=\"hull-trace\"></div>\n";
  out << "<h2>Broad phase per step</h2>\n<p>The original write-up's figure 2 for each replayed run: bodies, "
         "candidate pairs met by the broad-phase structure, pairs whose bounding spheres touch, SAT tests, "
         "intersecting pairs and contact points, per step, from the engine's step statistics. The "
         "structure that met the candidate pairs is the one the table names (a scenario's "
         "<code>world.broadPhase</code> forces one; by default worlds of at most 128 bodies run brute "
         "force).</p>\n"
      << StructureTable(file) << "<div class=\"plots\" id=\"broadphase\"></div>\n";
  out << "<pre id=\"report-status\"></pre>\n";
  out << "<script>" << ScriptSafe(kReportStatusScript) << "</script>\n";
  out << "<script type=\"application/json\" id=\"replay-data\">" << ScriptSafe(data.dump()) << "</script>\n";
  if (!threeLibrary.empty()) out << "<script>\n" << ScriptSafe(std::string(threeLibrary)) << "\n</script>\n";
  out << "<script>" << ScriptSafe(kReportReplayScript) << "</script>\n";
  return out.str();
}

Json ReplayRunsForPage(const ResultsFile& file) { return ReplayRunsJson(file); }

}  // namespace talus::harness
