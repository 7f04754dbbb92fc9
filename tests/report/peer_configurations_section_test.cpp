// The report's view of the peers' configurations (report_peers.h): the
// departures table, the "removed by the tuned configuration" cause lines
// (report_scorecard.h FailCauseLines), and the
// settings' two optional fields surviving results.json.
#include <gtest/gtest.h>

#include <cmath>

#include "report/report_peers.h"
#include "report/report_scorecard.h"
#include "talus/harness/report/report.h"
#include "talus/harness/run/results_file.h"

namespace talus::harness {
namespace peer_configurations_section_test {

MetricResult Metric(const std::string& name, double error, bool pass) {
  MetricResult m;
  m.name = name;
  m.unit = "m";
  m.measured = 1.0 + error;
  m.truth = 1.0;
  m.error = error;
  m.tolerance.absolute = 0.01;
  m.checked = true;
  m.pass = pass;
  return m;
}

RunResult Result(const std::string& backend, std::vector<MetricResult> metrics) {
  RunResult r;
  r.scenario = "box_slide_directions";
  r.file = "sliding/box_slide_directions.json";
  r.runId = "box_slide_directions[direction=30deg]";
  r.backend = backend;
  r.timeStep = 1.0 / 240.0;
  r.steps = 360;
  r.metrics = std::move(metrics);
  r.settings = {{"engine", "ODE"},
                {"friction directions", "along the slip", "world axes", "removes 24 FAILs"}};
  return r;
}

TEST(PeerSection, TunedNameAddsTheSuffixOnceOnly) {
  EXPECT_EQ(TunedName("ode-step"), "ode-step-tuned");
  EXPECT_EQ(TunedName("bullet-f32"), "bullet-f32-tuned");
  EXPECT_EQ(TunedName("ode-step-tuned"), "");
}

TEST(PeerSection, SaysForEachDefaultsFailWhetherTheTunedConfigurationRemovesIt) {
  const RunResult defaults = Result(
      "ode-step", {Metric("sliding_stop.distance", -0.192, false),
                   Metric("sliding_stop.lateral", 0.145, false), Metric("sliding_stop.time", 0.001, true)});
  const RunResult tuned = Result("ode-step-tuned", {Metric("sliding_stop.distance", 2.5e-11, true),
                                                    Metric("sliding_stop.lateral", 0.02, false),
                                                    Metric("sliding_stop.time", 0.0, true)});
  const std::map<std::string, const RunResult*> byBackend = {{"ode-step", &defaults},
                                                             {"ode-step-tuned", &tuned}};
  const std::string lines = FailCauseLines({"ode-step", "ode-step-tuned"}, byBackend);
  EXPECT_NE(lines.find("- `ode-step` FAILs sliding_stop.distance (-0.192): a setting: removed by "
                       "`ode-step-tuned` (2.5e-11)"),
            std::string::npos)
      << lines;
  EXPECT_NE(lines.find("- `ode-step` FAILs sliding_stop.lateral (0.145): the engine's own behaviour: not "
                       "removed by `ode-step-tuned` (0.02)"),
            std::string::npos)
      << lines;
  // Passing metrics get no line; the tuned configuration's own FAIL is the
  // engine's behaviour.
  EXPECT_EQ(lines.find("sliding_stop.time"), std::string::npos) << lines;
  EXPECT_NE(lines.find("- `ode-step-tuned` FAILs sliding_stop.lateral (0.02): the engine's own behaviour, in "
                       "its tuned configuration"),
            std::string::npos)
      << lines;
  // A tuned FAIL in a run its defaults pass entirely is the tuned settings'
  // doing; in a run the defaults also get wrong it is the engine's own.
  const RunResult slope = Result("ode-quickstep", {Metric("incline_slide.distance", -0.003, true)});
  const RunResult slopeTuned =
      Result("ode-quickstep-tuned", {Metric("incline_slide.distance", -0.07, false)});
  EXPECT_NE(
      FailCauseLines({"ode-quickstep", "ode-quickstep-tuned"},
                     {{"ode-quickstep", &slope}, {"ode-quickstep-tuned", &slopeTuned}})
          .find("- `ode-quickstep-tuned` FAILs incline_slide.distance (-0.07): the tuned settings add it: "
                "`ode-quickstep` passes (-0.003)"),
      std::string::npos);
  const RunResult column = Result("ode-step", {Metric("h1", 0.0, true), Metric("h2", -1.0, false)});
  const RunResult columnTuned =
      Result("ode-step-tuned", {Metric("h1", -0.5, false), Metric("h2", -1.0, false)});
  EXPECT_NE(
      FailCauseLines({"ode-step", "ode-step-tuned"},
                     {{"ode-step", &column}, {"ode-step-tuned", &columnTuned}})
          .find("- `ode-step-tuned` FAILs h1 (-0.5): the engine's own behaviour: `ode-step` passes this "
                "truth (0) but FAILs 1 other truths of this run"),
      std::string::npos);
  // Without the tuned run the cause cannot be put on a setting.
  EXPECT_NE(FailCauseLines({"ode-step"}, {{"ode-step", &defaults}})
                .find("the engine's own behaviour in this configuration (no `-tuned` counterpart ran)"),
            std::string::npos);
}

TEST(PeerSection, DeparturesTableListsOnlySettingsWithAnEngineDefault) {
  const std::string table = DeparturesTable(Result("ode-step-tuned", {}).settings);
  EXPECT_NE(table.find("| friction directions | along the slip | world axes | removes 24 FAILs |"),
            std::string::npos)
      << table;
  EXPECT_EQ(table.find("| engine |"), std::string::npos) << table;
  EXPECT_EQ(DeparturesTable({{"engine", "ODE"}}), "");
  // A pipe in a value would split the cell: it is replaced.
  EXPECT_NE(DeparturesTable({{"a", "x | y", "z", "w"}}).find("| a | x / y | z | w |"), std::string::npos);
}

TEST(PeerSection, SummaryShowsBothAndResultsJsonKeepsTheFields) {
  ResultsFile file;
  file.backends = {"ode-step", "ode-step-tuned"};
  file.results = {Result("ode-step", {Metric("sliding_stop.distance", -0.192, false)}),
                  Result("ode-step-tuned", {Metric("sliding_stop.distance", 2.5e-11, true)})};
  const std::string md = SummaryMarkdown(file);
  EXPECT_NE(md.find("FAILs and their cause:"), std::string::npos) << md;
  EXPECT_NE(md.find("removed by `ode-step-tuned`"), std::string::npos) << md;
  EXPECT_NE(md.find("Departures from the engine's defaults:"), std::string::npos) << md;

  auto back = ResultsFromJson(ResultsToJson(file));
  ASSERT_TRUE(back) << back.GetError().message;
  const Setting& departure = back.Value().results[0].settings[1];
  EXPECT_EQ(departure.engineDefault, "world axes");
  EXPECT_EQ(departure.effect, "removes 24 FAILs");
  EXPECT_EQ(back.Value().results[0].settings[0].engineDefault, "");
}

}  // namespace peer_configurations_section_test
}  // namespace talus::harness
