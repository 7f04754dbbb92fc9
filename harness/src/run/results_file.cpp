// Writing and reading results.json and its trajectory and replay files (see
// results_file.h). Reading walks the document with a path so that a
// malformed file is reported at the exact place (results_json_walk.h); the
// walk throws an exception that never leaves the reader.
#include "talus/harness/run/results_file.h"

#include "talus/harness/support/atomic_file.h"

#include "talus/harness/run/display_trajectory.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "run/results_json_walk.h"
#include "run/results_tables.h"
#include "support/text_util.h"

namespace talus::harness {
namespace {

using namespace results_json;

// How a writer puts NaN and infinities: results.json as JSON's null (JSON
// has neither), the wire between a job's process and the runner
// (RunResultToWire) as they are (CBOR keeps both), so a result that crossed
// it is the one computed.
enum class NonFinite {
  AsNull,
  Kept,
};

Json Number(double value, NonFinite nonFinite) {
  return std::isfinite(value) || nonFinite == NonFinite::Kept ? Json(value) : Json(nullptr);
}

Json NumbersOrNull(const std::vector<double>& values, NonFinite nonFinite) {
  Json array = Json::array();
  for (double value : values) array.push_back(Number(value, nonFinite));
  return array;
}

// A metric of `run`: in full when `tables` is null (the wire's record);
// else what was measured, naming its definition (name, unit, tolerance,
// published figure) in `run`'s list of `tables`.
Json MetricToJson(const MetricResult& m, ResultsTableWriter* tables, const std::string& run,
                  NonFinite nonFinite) {
  Json j;
  if (tables == nullptr) {
    j["name"] = m.name;
    j["unit"] = m.unit;
  } else {
    j["definition"] = tables->MetricDefinition(run, m);
  }
  j["measured"] = Number(m.measured, nonFinite);
  j["truth"] = Number(m.truth, nonFinite);
  j["truthIntegrator"] = Number(m.truthIntegrator, nonFinite);
  j["error"] = Number(m.error, nonFinite);
  if (tables == nullptr) j["tolerance"] = ToleranceToJson(m);
  j["checked"] = m.checked;
  j["pass"] = m.pass;
  j["ungated"] = m.ungated;
  // Only metrics of a truth with a published figure carry one.
  if (tables == nullptr && !std::isnan(m.publishedValue))
    j["published"] = PublishedToJson(m, nonFinite == NonFinite::Kept);
  return j;
}

// A result's trajectory: its plot series and, when recorded and
// `withReplay`, its replay; in the display form of display_trajectory.h
// unless `exact`.
void TrajectoryToJson(const RunResult& r, Json& j, NonFinite nonFinite, bool exact = true,
                      bool withReplay = true) {
  const PlotSeries shown = exact ? r.series : DisplaySeries(r.series);
  Json series;
  series["time"] = shown.time;
  series["heights"] = shown.heights;
  series["energy"] = Json::array();
  for (double e : shown.energy) series["energy"].push_back(Number(e, nonFinite));
  j["series"] = series;
  // Only runs recorded for replay carry one, so other files are unchanged.
  if (withReplay && !r.replay.frames.empty()) {
    j["replay"] = ReplayToJson(exact ? r.replay : DisplayReplay(r.replay));
  }
}

// The result; its trajectory too when `withTrajectory` (the one-text form).
// In full when `tables` is null (the wire's record); else its settings and
// its metrics' definitions go into `tables` and it names them.
Json ResultToJson(const RunResult& r, bool withTrajectory, ResultsTableWriter* tables, NonFinite nonFinite) {
  Json j;
  j["scenario"] = r.scenario;
  j["file"] = r.file;
  j["run"] = r.runId;
  j["backend"] = r.backend;
  j["sweep"] = Json::array();
  for (const SweepValue& v : r.sweepValues) j["sweep"].push_back({{"name", v.name}, {"value", v.value}});
  j["timeStep"] = r.timeStep;
  j["iterations"] = r.iterations;
  j["steps"] = r.steps;
  j["bodies"] = r.bodyNames;
  if (tables != nullptr) {
    j["settings"] = tables->SettingsList(r.backend, r.settings);
  } else {
    j["settings"] = Json::array();
    for (const Setting& s : r.settings) j["settings"].push_back(SettingToJson(s));
  }
  j["error"] = r.error;
  j["metrics"] = Json::array();
  for (const MetricResult& m : r.metrics) j["metrics"].push_back(MetricToJson(m, tables, r.runId, nonFinite));
  j["wallSecondsPerStep"] = {{"median", r.wallSecondsPerStepMedian}, {"mean", r.wallSecondsPerStepMean}};
  j["wallSeconds"] = {{"total", r.wallSeconds}, {"longestStep", Number(r.wallSecondsLongestStep, nonFinite)}};
  // Only sweep points run with perturbed copies carry this, so files of
  // other runs (and sweeps with --perturb-copies 0) are unchanged. An
  // infinite spread (some copies unmeasured) is written as null.
  if (r.perturbed.copies > 0) {
    j["perturbed"] = {{"copies", r.perturbed.copies},
                      {"amount", r.perturbed.amount},
                      {"errorSpread", Number(r.perturbed.errorSpread, nonFinite)},
                      {"runSeconds", r.perturbed.runSeconds},
                      {"errors", NumbersOrNull(r.perturbed.errors, nonFinite)}};
  }
  if (withTrajectory) TrajectoryToJson(r, j, nonFinite);
  return j;
}

// A metric of `run`: in full when `tables` is null, else with its
// definition from `run`'s list of `tables`.
MetricResult MetricFromJson(const Json& j, const std::string& where, const ResultsTables* tables,
                            const std::string& run) {
  MetricResult m;
  if (tables == nullptr) {
    m = MakeMetric(GetString(j, "name", where), GetString(j, "unit", where));
    ToleranceAndPublishedFromJson(j, where, m);
  } else {
    m = tables->Definition(run, Field(j, "definition", where), Place(where, "definition"));
  }
  m.measured = GetNumber(j, "measured", where);
  m.truth = GetNumber(j, "truth", where);
  m.truthIntegrator = GetNumber(j, "truthIntegrator", where);
  m.error = GetNumber(j, "error", where);
  m.checked = GetBool(j, "checked", where);
  m.pass = GetBool(j, "pass", where);
  m.ungated = GetString(j, "ungated", where);
  return m;
}

// Reads the trajectory fields (series, and replay if present) of `j` into `r`.
void TrajectoryFromJson(const Json& j, const std::string& where, RunResult& r) {
  const Json& series = Field(j, "series", where);
  const std::string at = Place(where, "series");
  r.series.time = GetNumbers(series, "time", at);
  r.series.energy = GetNumbers(series, "energy", at);
  const Json& heights = GetArray(series, "heights", at);
  for (std::size_t i = 0; i < heights.size(); ++i) {
    Json wrapper;
    wrapper["h"] = heights[i];
    r.series.heights.push_back(GetNumbers(wrapper, "h", Concat({at, "/heights/", std::to_string(i)})));
  }
  if (j.contains("replay")) {
    auto replay = ReplayFromJson(j["replay"], Place(where, "replay"));
    if (!replay) throw ResultsParseFailure{replay.GetError().message};
    r.replay = std::move(replay).Value();
  }
}

// The result; its trajectory too when `withTrajectory` (the one-text form).
// In full when `tables` is null (the wire's record); else naming its
// settings and its metrics' definitions in `tables`.
RunResult ResultFromJson(const Json& j, const std::string& where, bool withTrajectory,
                         const ResultsTables* tables) {
  RunResult r;
  r.scenario = GetString(j, "scenario", where);
  r.file = GetString(j, "file", where);
  r.runId = GetString(j, "run", where);
  r.backend = GetString(j, "backend", where);
  const Json& sweep = GetArray(j, "sweep", where);
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    const std::string at = Concat({where, "/sweep/", std::to_string(i)});
    r.sweepValues.push_back({GetString(sweep[i], "name", at), GetString(sweep[i], "value", at)});
  }
  r.timeStep = GetNumber(j, "timeStep", where);
  r.iterations = GetInt(j, "iterations", where);
  r.steps = GetInt(j, "steps", where);
  for (const Json& name : GetArray(j, "bodies", where)) {
    if (!name.is_string()) throw ResultsParseFailure{Concat({where, "/bodies: expected strings"})};
    r.bodyNames.push_back(name.get<std::string>());
  }
  if (tables != nullptr) {
    r.settings = tables->Settings(r.backend, Field(j, "settings", where), Place(where, "settings"));
  } else {
    const Json& settings = GetArray(j, "settings", where);
    for (std::size_t i = 0; i < settings.size(); ++i) {
      r.settings.push_back(SettingFromJson(settings[i], Concat({where, "/settings/", std::to_string(i)})));
    }
  }
  r.error = GetString(j, "error", where);
  const Json& metrics = GetArray(j, "metrics", where);
  for (std::size_t i = 0; i < metrics.size(); ++i) {
    r.metrics.push_back(
        MetricFromJson(metrics[i], Concat({where, "/metrics/", std::to_string(i)}), tables, r.runId));
  }
  const Json& wall = Field(j, "wallSecondsPerStep", where);
  r.wallSecondsPerStepMedian = GetNumber(wall, "median", Place(where, "wallSecondsPerStep"));
  r.wallSecondsPerStepMean = GetNumber(wall, "mean", Place(where, "wallSecondsPerStep"));
  if (j.contains("wallSeconds")) {
    const Json& total = Field(j, "wallSeconds", where);
    r.wallSeconds = GetNumber(total, "total", Place(where, "wallSeconds"));
    r.wallSecondsLongestStep = GetNumber(total, "longestStep", Place(where, "wallSeconds"));
  } else {
    // Files written before the total was recorded: the mean over the timed
    // steps times the steps estimates it; the longest step is unknown.
    r.wallSeconds = r.wallSecondsPerStepMean * r.steps;
    r.wallSecondsLongestStep = std::numeric_limits<double>::quiet_NaN();
  }
  if (j.contains("perturbed")) {
    // Only sweep points run with perturbed copies carry the block.
    const Json& perturbed = Field(j, "perturbed", where);
    const std::string place = Place(where, "perturbed");
    r.perturbed.copies = GetInt(perturbed, "copies", place);
    r.perturbed.amount = GetNumber(perturbed, "amount", place);
    const double spread = GetNumber(perturbed, "errorSpread", place);
    r.perturbed.errorSpread = std::isnan(spread) ? std::numeric_limits<double>::infinity() : spread;
    r.perturbed.runSeconds = GetNumbers(perturbed, "runSeconds", place);
    // Every version-2 writer keeps the copies' errors, so a block without
    // them is malformed rather than old.
    // null: a run that failed or was not measured, an infinite error.
    r.perturbed.errors = GetNumbers(perturbed, "errors", place);
    for (double& error : r.perturbed.errors) {
      if (std::isnan(error)) error = std::numeric_limits<double>::infinity();
    }
    if (r.perturbed.errors.size() != r.perturbed.runSeconds.size()) {
      throw ResultsParseFailure{Concat({place, ": need one error per run (copies + 1)"})};
    }
    if (r.perturbed.copies < 1 ||
        r.perturbed.runSeconds.size() != static_cast<std::size_t>(r.perturbed.copies) + 1 ||
        !(r.perturbed.errorSpread >= 0.0)) {
      throw ResultsParseFailure{
          Concat({place, ": need copies >= 1, copies + 1 runSeconds and errorSpread >= 0"})};
    }
  }
  if (withTrajectory) TrajectoryFromJson(j, where, r);
  return r;
}

// results.json's top level, and each result with or without its trajectory.
Json ResultsJson(const ResultsFile& file, bool withTrajectories) {
  Json j;
  j["format"] = kResultsFormat;
  j["version"] = kResultsVersion;
  j["deterministic"] = file.deterministic;
  j["backends"] = file.backends;
  // Only the file form says so: its trajectories are in the trajectory file.
  if (!withTrajectories) j["trajectories"] = file.results.size();
  // The tables come before the results that fill them (results_tables.h).
  ResultsTableWriter tables;
  Json results = Json::array();
  for (const RunResult& r : file.results)
    results.push_back(ResultToJson(r, withTrajectories, &tables, NonFinite::AsNull));
  j["settings"] = tables.SettingsJson();
  j["metricDefinitions"] = tables.MetricDefinitionsJson();
  j["results"] = std::move(results);
  return j;
}

std::size_t ReplayCount(const ResultsFile& file) {
  return static_cast<std::size_t>(std::count_if(file.results.begin(), file.results.end(),
                                                [](const RunResult& r) { return !r.replay.frames.empty(); }));
}

// Whether the trajectories are written exact: asked for, or read from a
// display-form file (rounding them twice could move a value by a step).
bool WrittenExact(const ResultsFile& file) { return file.fullTrajectories || file.trajectoriesInDisplayForm; }

// The trajectory file's text: one line per result (compact: a trajectory
// is hundreds to thousands of numbers, which an indented file would put one
// per line), in the results' order; "replays" says how many lines the
// replay file holds.
std::string TrajectoriesToJson(const ResultsFile& file) {
  Json head;
  head["format"] = kTrajectoriesFormat;
  head["version"] = kTrajectoriesVersion;
  head["resolution"] = file.fullTrajectories ? "full" : "display";
  head["replays"] = ReplayCount(file);
  std::string text = head.dump();
  text.pop_back();  // the closing brace: the trajectories follow
  text += ",\"trajectories\":[";
  for (std::size_t i = 0; i < file.results.size(); ++i) {
    const RunResult& r = file.results[i];
    Json line;
    line["result"] = i;
    line["run"] = r.runId;
    line["backend"] = r.backend;
    TrajectoryToJson(r, line, NonFinite::AsNull, WrittenExact(file), false);
    text += Concat({i == 0 ? "\n" : ",\n", line.dump()});
  }
  return text + "\n]}\n";
}

// The replay file's text: one line per result recorded for replay, in the
// results' order, each naming its result.
std::string ReplaysToJson(const ResultsFile& file) {
  Json head;
  head["format"] = kReplaysFormat;
  head["version"] = kReplaysVersion;
  std::string text = head.dump();
  text.pop_back();  // the closing brace: the replays follow
  text += ",\"replays\":[";
  bool first = true;
  for (std::size_t i = 0; i < file.results.size(); ++i) {
    const RunResult& r = file.results[i];
    if (r.replay.frames.empty()) continue;
    Json line;
    line["result"] = i;
    line["run"] = r.runId;
    line["backend"] = r.backend;
    line["replay"] = ReplayToJson(WrittenExact(file) ? r.replay : DisplayReplay(r.replay));
    text += Concat({first ? "\n" : ",\n", line.dump()});
    first = false;
  }
  return text + (first ? "]}\n" : "\n]}\n");
}

// Puts each line of the replay file into its result: `expected` lines, in
// increasing result order, each naming its result's run and backend.
void ReadReplays(const Json& j, std::size_t expected, ResultsFile& file) {
  if (GetString(j, "format", "") != kReplaysFormat) {
    throw ResultsParseFailure{Concat({"/format: not a \"", kReplaysFormat, "\" file"})};
  }
  if (GetInt(j, "version", "") != kReplaysVersion) {
    throw ResultsParseFailure{Concat({"/version: unsupported, expected ", std::to_string(kReplaysVersion)})};
  }
  const Json& lines = GetArray(j, "replays", "");
  if (lines.size() != expected) {
    throw ResultsParseFailure{Concat({"/replays: ", std::to_string(lines.size()),
                                      " replays where the trajectory file says ", std::to_string(expected)})};
  }
  int previous = -1;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string where = Concat({"/replays/", std::to_string(i)});
    const int index = GetInt(lines[i], "result", where);
    if (index <= previous || index >= static_cast<int>(file.results.size())) {
      throw ResultsParseFailure{Concat({where, ": result ", std::to_string(index), " is not after result ",
                                        std::to_string(previous), " and within the ",
                                        std::to_string(file.results.size()), " results"})};
    }
    previous = index;
    RunResult& r = file.results[static_cast<std::size_t>(index)];
    if (GetString(lines[i], "run", where) != r.runId || GetString(lines[i], "backend", where) != r.backend) {
      throw ResultsParseFailure{Concat({where, ": not the replay of result ", std::to_string(index), " (",
                                        r.runId, " with ", r.backend, ")"})};
    }
    auto replay = ReplayFromJson(Field(lines[i], "replay", where), Place(where, "replay"));
    if (!replay) throw ResultsParseFailure{replay.GetError().message};
    r.replay = std::move(replay).Value();
  }
}

// Puts each line of the trajectory file into its result, checking that
// there is one per result, in order, naming the result's run and backend.
// Returns the number of replays its replay file holds, or -1 for a file
// written before the replays had their own (they are inside its lines).
int ReadTrajectories(const Json& j, ResultsFile& file) {
  if (GetString(j, "format", "") != kTrajectoriesFormat) {
    throw ResultsParseFailure{Concat({"/format: not a \"", kTrajectoriesFormat, "\" file"})};
  }
  if (GetInt(j, "version", "") != kTrajectoriesVersion) {
    throw ResultsParseFailure{
        Concat({"/version: unsupported, expected ", std::to_string(kTrajectoriesVersion)})};
  }
  // Files written before the display form have no "resolution" and are exact.
  const std::string resolution = j.contains("resolution") ? GetString(j, "resolution", "") : "full";
  if (resolution != "full" && resolution != "display") {
    throw ResultsParseFailure{
        Concat({"/resolution: \"", resolution, "\", expected \"full\" or \"display\""})};
  }
  file.fullTrajectories = resolution == "full";
  file.trajectoriesInDisplayForm = !file.fullTrajectories;
  const Json& lines = GetArray(j, "trajectories", "");
  if (lines.size() != file.results.size()) {
    throw ResultsParseFailure{
        Concat({"/trajectories: ", std::to_string(lines.size()), " trajectories for a results file of ",
                std::to_string(file.results.size()), " results"})};
  }
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string where = Concat({"/trajectories/", std::to_string(i)});
    RunResult& r = file.results[i];
    if (GetInt(lines[i], "result", where) != static_cast<int>(i) ||
        GetString(lines[i], "run", where) != r.runId || GetString(lines[i], "backend", where) != r.backend) {
      throw ResultsParseFailure{Concat({where, ": not the trajectory of result ", std::to_string(i), " (",
                                        r.runId, " with ", r.backend, ")"})};
    }
    TrajectoryFromJson(lines[i], where, r);
  }
  if (!j.contains("replays")) return -1;
  const int replays = GetInt(j, "replays", "");
  if (replays < 0) throw ResultsParseFailure{"/replays: expected a count >= 0"};
  return replays;
}

// The trajectory file's text, read only when results.json is in the file
// form, and the name its errors carry.
struct TrajectorySource {
  std::string name;
  std::function<Result<std::string>()> read;
};

Result<ResultsFile> ParseResults(std::string_view text, const TrajectorySource& source,
                                 const TrajectorySource& replaySource) {
  const Json j = Json::parse(text, nullptr, false);
  if (j.is_discarded()) return Error{"not valid JSON"};
  ResultsFile file;
  bool split = false;
  try {
    if (GetString(j, "format", "") != kResultsFormat) {
      return Error{Concat({"/format: not a \"", kResultsFormat, "\" file"})};
    }
    if (const int version = GetInt(j, "version", ""); version != kResultsVersion) {
      return Error{
          Concat({"/version: ", std::to_string(version), ", expected ", std::to_string(kResultsVersion),
                  version < kResultsVersion ? " (an older build's file: run it again with this build)"
                                            : " (a newer build's file)"})};
    }
    file.deterministic = GetBool(j, "deterministic", "");
    for (const Json& name : GetArray(j, "backends", "")) {
      if (!name.is_string()) return Error{"/backends: expected strings"};
      file.backends.push_back(name.get<std::string>());
    }
    split = j.contains("trajectories");
    const Json& results = GetArray(j, "results", "");
    if (split && GetInt(j, "trajectories", "") != static_cast<int>(results.size())) {
      return Error{"/trajectories: expected the number of results"};
    }
    const ResultsTables tables = ResultsTables::Read(j);
    for (std::size_t i = 0; i < results.size(); ++i) {
      file.results.push_back(
          ResultFromJson(results[i], Concat({"/results/", std::to_string(i)}), !split, &tables));
    }
  } catch (const ResultsParseFailure& failure) {
    return Error{failure.message};
  }
  if (!split) {
    file.fullTrajectories = true;  // the one-text form keeps every number
    return file;
  }
  auto trajectoryText = source.read();
  if (!trajectoryText) return Error{Concat({"its trajectories: ", trajectoryText.GetError().message})};
  const Json trajectories = Json::parse(trajectoryText.Value(), nullptr, false);
  if (trajectories.is_discarded()) return Error{Concat({source.name, ": not valid JSON"})};
  int replays = -1;
  try {
    replays = ReadTrajectories(trajectories, file);
  } catch (const ResultsParseFailure& failure) {
    return Error{Concat({source.name, ": ", failure.message})};
  }
  if (replays < 0) return file;
  auto replayText = replaySource.read();
  if (!replayText) return Error{Concat({"its replays: ", replayText.GetError().message})};
  const Json replayJson = Json::parse(replayText.Value(), nullptr, false);
  if (replayJson.is_discarded()) return Error{Concat({replaySource.name, ": not valid JSON"})};
  try {
    ReadReplays(replayJson, static_cast<std::size_t>(replays), file);
  } catch (const ResultsParseFailure& failure) {
    return Error{Concat({replaySource.name, ": ", failure.message})};
  }
  return file;
}

}  // namespace

std::optional<std::pair<std::size_t, std::size_t>> FindDuplicatedResult(
    const std::vector<RunResult>& results) {
  std::map<std::pair<std::string_view, std::string_view>, std::size_t> first;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const auto [at, inserted] =
        first.emplace(std::pair<std::string_view, std::string_view>(results[i].runId, results[i].backend), i);
    if (!inserted) return std::pair{at->second, i};
  }
  return std::nullopt;
}

std::string ResultsToJson(const ResultsFile& file) { return ResultsJson(file, true).dump(2) + "\n"; }

Result<ResultsFile> ResultsFromJson(std::string_view text, std::string_view trajectoryText,
                                    std::string_view replayText) {
  return ParseResults(text,
                      {"trajectory file",
                       [trajectoryText]() -> Result<std::string> {
                         if (trajectoryText.empty()) return Error{"no trajectory file was given"};
                         return std::string(trajectoryText);
                       }},
                      {"replay file", [replayText]() -> Result<std::string> {
                         if (replayText.empty()) return Error{"no replay file was given"};
                         return std::string(replayText);
                       }});
}

std::filesystem::path TrajectoryFilePath(const std::filesystem::path& resultsPath) {
  std::filesystem::path path = resultsPath;
  if (path.extension() == ".json") path.replace_extension();
  path += ".trajectories.json";
  return path;
}

std::filesystem::path ReplayFilePath(const std::filesystem::path& resultsPath) {
  std::filesystem::path path = resultsPath;
  if (path.extension() == ".json") path.replace_extension();
  path += ".replays.json";
  return path;
}

std::vector<FileText> ResultsFileTexts(const std::filesystem::path& path, const ResultsFile& file) {
  return {{path, ResultsJson(file, false).dump(2) + "\n"},
          {TrajectoryFilePath(path), TrajectoriesToJson(file)},
          {ReplayFilePath(path), ReplaysToJson(file)}};
}

std::string RunResultToWire(const RunResult& result) {
  const std::vector<std::uint8_t> bytes = Json::to_cbor(ResultToJson(result, true, nullptr, NonFinite::Kept));
  return {bytes.begin(), bytes.end()};
}

Result<RunResult> RunResultFromWire(std::string_view bytes) {
  const Json j = Json::from_cbor(bytes.begin(), bytes.end(), true, false);
  if (j.is_discarded()) return Error{"not a serialised run result"};
  try {
    return ResultFromJson(j, "result", true, nullptr);
  } catch (const ResultsParseFailure& failure) {
    return Error{failure.message};
  }
}

Result<std::monostate> WriteResultsFile(const std::filesystem::path& path, const ResultsFile& file) {
  return WriteFilesAtomically(ResultsFileTexts(path, file));
}

Result<ResultsFile> ReadResultsFile(const std::filesystem::path& path) {
  auto text = ReadTextFile(path, "the results file");
  if (!text) return text.GetError();
  const std::filesystem::path trajectoryPath = TrajectoryFilePath(path);
  const std::filesystem::path replayPath = ReplayFilePath(path);
  auto file = ParseResults(
      text.Value(),
      {trajectoryPath.string(),
       [&trajectoryPath] { return ReadTextFile(trajectoryPath, "the trajectory file"); }},
      {replayPath.string(), [&replayPath] { return ReadTextFile(replayPath, "the replay file"); }});
  if (!file) return Error{Concat({path.string(), ": ", file.GetError().message})};
  return file;
}

}  // namespace talus::harness
