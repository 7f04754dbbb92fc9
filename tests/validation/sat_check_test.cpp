// Talus's SAT against the exact truth on a few hundred generated pairs, and
// the structure of the reports the comparison document reads.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "collision/sat.h"
#include "sat_check.h"

namespace talus::validation {
namespace {

const SatCheckReport& SmallReport() {
  static const SatCheckReport report = [] {
    SatCheckSettings settings;
    settings.pairs = 200;
    settings.seed = 5;
    settings.timingRepeats = 0;
    return RunSatCheck(settings).Value();
  }();
  return report;
}

TEST(SatCheck, TalusVerdictsAgreeWithTruthOutsideTheTouchingBand) {
  for (const MethodReport& m : SmallReport().methods) {
    if (m.family != "talus") continue;
    EXPECT_EQ(m.disagree, 0) << m.name;
    EXPECT_EQ(m.oracleFailures, 0) << m.name;
    EXPECT_EQ(m.agree + m.touchingBandDisagree, SmallReport().pairCount) << m.name;
  }
}

TEST(SatCheck, TalusDepthAndNormalWithinAxisPreferenceTolerance) {
  // The SAT may keep a face axis up to kAxisPreferenceTolerance shallower
  // than the true minimum; add 1e-9 m of round-off.
  const double tolerance = kAxisPreferenceTolerance + 1e-9;
  for (const MethodReport& m : SmallReport().methods) {
    if (m.family != "talus") continue;
    EXPECT_GT(m.depthError.count, 20) << m.name;
    EXPECT_LE(m.depthError.max, tolerance) << m.name;
    EXPECT_LE(m.normalExcess.max, tolerance) << m.name;
  }
}

TEST(SatCheck, TruthAgreesWithQhullAndBoxClosedForms) {
  const TruthReport& t = SmallReport().truth;
  EXPECT_EQ(t.qhullChecks, SmallReport().pairCount);
  EXPECT_GT(t.boxClosedFormChecks, 0);
  EXPECT_LE(t.boxClosedFormMaxError, 1e-12);
  EXPECT_EQ(t.boxClosedFormVerdictMismatches, 0);
  EXPECT_GT(t.intersecting, 20);
}

TEST(SatCheck, SameSeedGivesTheSameReport) {
  SatCheckSettings settings;
  settings.pairs = 200;
  settings.seed = 5;
  settings.timingRepeats = 0;
  const SatCheckReport again = RunSatCheck(settings).Value();
  EXPECT_EQ(ReportToJson(again), ReportToJson(SmallReport()));
}

TEST(SatCheck, RefusesBadSettings) {
  SatCheckSettings settings;
  settings.pairs = 0;
  const auto result = RunSatCheck(settings);
  ASSERT_FALSE(result.Ok());
  EXPECT_NE(result.GetError().message.find("pairs"), std::string::npos);
}

TEST(SatCheck, JsonAndMarkdownHaveTheDocumentedStructure) {
  const auto json = nlohmann::json::parse(ReportToJson(SmallReport()));
  for (const char* key : {"settings", "pairCount", "placements", "alignments", "truth", "methods", "pairs"})
    EXPECT_TRUE(json.contains(key)) << key;
  ASSERT_EQ(json["methods"].size(), SmallReport().methods.size());
  for (const auto& m : json["methods"]) {
    for (const char* key : {"name", "family", "verdict", "depthError", "normalAngle", "normalExcess",
                            "pointOutside", "timeNs", "timeVsAccuracy", "worstDepth", "disagreements"})
      EXPECT_TRUE(m.contains(key)) << key;
  }
  EXPECT_EQ(json["pairs"].size(), 200u);
  EXPECT_EQ(json["pairs"][0]["results"].size(), SmallReport().methods.size());
  const std::string markdown = ReportToMarkdown(SmallReport());
  EXPECT_EQ(markdown.rfind("## SAT validation", 0), 0u);
  EXPECT_NE(markdown.find("### Verdicts"), std::string::npos);
  EXPECT_NE(markdown.find("| talus-pruned-clipped-cached |"), std::string::npos);
  EXPECT_NE(markdown.find("| ccd-gjk-penetration |"), std::string::npos);
}

}  // namespace
}  // namespace talus::validation
