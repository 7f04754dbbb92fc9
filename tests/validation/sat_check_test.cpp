// Talus's SAT against the exact truth on a few hundred generated pairs, and
// the structure of the reports the comparison document reads.
#include <gtest/gtest.h>

#include <algorithm>

#include <nlohmann/json.hpp>

#include "collision/sat.h"
#include "sat_check.h"

namespace talus::validation {
namespace sat_check_test {

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

TEST(SatCheck, TalusDepthNormalAndPointsWithinTheStatedBounds) {
  // The gate's per-pair bounds (sat_check.h): depth and normal excess within
  // the SAT's preference band + 1e-9 of the size + round-off; no point
  // deeper than the depth; points inside both shapes.
  for (const MethodReport& m : SmallReport().methods) {
    if (m.family != "talus") continue;
    EXPECT_GT(m.depthError.count, 20) << m.name;
    EXPECT_EQ(m.depthOverBound, 0) << m.name;
    EXPECT_EQ(m.normalOverBound, 0) << m.name;
    EXPECT_EQ(m.deepestPointDeeper, 0) << m.name;
    EXPECT_EQ(m.pointsOutsideBoth, 0) << m.name;
    // Clipped modes: every point inside both shapes to round-off (issue 26).
    if (m.name.find("clipped") != std::string::npos) {
      EXPECT_EQ(m.pointsOutsideEither, 0) << m.name;
    }
    ASSERT_EQ(m.families.size(), static_cast<std::size_t>(kFamilyCount)) << m.name;
  }
  EXPECT_TRUE(SmallReport().failures.empty()) << SummaryLine(SmallReport());
}

TEST(SatCheck, EveryFamilyIsGenerated) {
  const std::vector<ShapePair> pairs = GeneratePairs(2 * kFamilyCount, 3);
  for (int i = 0; i < 2 * kFamilyCount; ++i)
    EXPECT_EQ(static_cast<int>(pairs[static_cast<std::size_t>(i)].family), i % kFamilyCount);
  // Scaled shapes span about 1 mm to 10 m across (a hull's points may miss
  // the ellipsoid's widest part, so sizes can fall a little below 5e-4 m);
  // far pairs sit 1e4-1e5 m out.
  double smallest = 1e9;
  double largest = 0.0;
  for (const ShapePair& p : GeneratePairs(600, 3)) {
    if (p.family == Family::Scaled) {
      smallest = std::min(smallest, p.size);
      largest = std::max(largest, p.size);
      EXPECT_LE(p.size, 5.0 * 1.001);
    }
    if (p.family == Family::Far) {
      EXPECT_GE(p.xfA.position.norm(), 1e4 * 0.999);
      EXPECT_LE(p.xfA.position.norm(), 1e5 * 1.001);
    }
    if (p.family == Family::Identical) {
      EXPECT_EQ(&p.a.GetHull(), &p.b.GetHull());
    }
  }
  EXPECT_LT(smallest, 2e-3);
  EXPECT_GT(largest, 2.0);
}

// The class issue 26 found contact points outside the shapes in: large
// shapes with a face of B nearly anti-parallel to a face of A, twists
// spanning 1e-8 to 1e-6 rad.
TEST(SatCheck, LargeParallelPairsHaveNearlyParallelFacesOfLargeShapes) {
  double smallest = 1.0;
  double largest = 0.0;
  int count = 0;
  for (const ShapePair& p : GeneratePairs(700, 3)) {
    if (p.family != Family::LargeParallel) continue;
    ++count;
    EXPECT_GE(p.twist, kLargeParallelTwistMin);
    EXPECT_LE(p.twist, kLargeParallelTwistMax);
    smallest = std::min(smallest, p.twist);
    largest = std::max(largest, p.twist);
    // Largest half extents drawn in [2, 3] m; a hull's points need not
    // reach its ellipsoid's widest part, so its box is a little smaller.
    EXPECT_GE(p.size, 1.0);
    EXPECT_LE(p.size, 3.0 * 1.001);
    // Some face of B is anti-parallel to some face of A to within the
    // twist (plus round-off of the rotations, 1e-12 rad).
    double closest = 4.0;
    for (const HullFace& fa : p.a.GetHull().Faces()) {
      const Vec3 na = p.xfA.rotation * fa.plane.normal;
      for (const HullFace& fb : p.b.GetHull().Faces())
        closest = std::min(closest, (na + p.xfB.rotation * fb.plane.normal).norm());
    }
    EXPECT_LE(closest, p.twist * (1.0 + 1e-6) + 1e-12);
  }
  EXPECT_EQ(count, 100);
  EXPECT_LT(smallest, 2e-8);
  EXPECT_GT(largest, 5e-7);
}

TEST(SatCheck, TruthAgreesWithQhullAndBoxClosedForms) {
  const TruthReport& t = SmallReport().truth;
  EXPECT_EQ(t.qhullChecks, SmallReport().pairCount);
  // Agreed, not only ran: the qhull truth and BuildHull give the same
  // hull (volume to 1e-9, each inside the other) on every pair.
  EXPECT_EQ(t.qhullMismatches, 0);
  EXPECT_TRUE(t.qhullMessages.empty()) << t.qhullMessages.front();
  EXPECT_TRUE(SmallReport().truthBroken.empty()) << SummaryLine(SmallReport());
  EXPECT_GT(t.boxClosedFormChecks, 0);
  EXPECT_LE(t.boxClosedFormMaxError, 1e-12);
  EXPECT_EQ(t.boxClosedFormVerdictMismatches, 0);
  EXPECT_GT(t.intersecting, 20);
}

// The gate's exit status: a broken truth outranks a broken bound, which
// outranks a pass; the summary line says which.
TEST(SatCheck, ExitStatusPutsABrokenTruthFirst) {
  SatCheckReport report;
  EXPECT_EQ(ExitStatus(report), kExitPassed);
  EXPECT_EQ(SummaryLine(report).rfind("PASS", 0), 0u);
  report.failures.push_back("talus-pruned-clipped: error on pair 3");
  EXPECT_EQ(ExitStatus(report), kExitBoundBroken);
  EXPECT_EQ(SummaryLine(report).rfind("FAIL", 0), 0u);
  report.truthBroken.push_back("Minkowski hull (qhull) vs BuildHull, pair 3: volume");
  EXPECT_EQ(ExitStatus(report), kExitTruthBroken);
  EXPECT_EQ(SummaryLine(report).rfind("TRUTH BROKEN", 0), 0u);
  EXPECT_NE(kExitTruthBroken, kExitUsage);
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
  // Past the stated limit: refused before anything is allocated, with the
  // limit in the message.
  settings.pairs = kMaxPairs + 1;
  const auto huge = RunSatCheck(settings);
  ASSERT_FALSE(huge.Ok());
  EXPECT_NE(huge.GetError().message.find(std::to_string(kMaxPairs)), std::string::npos);
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

// --seed is a whole number 0..2^64-1: a sign, junk or overflow is refused
// with the text quoted, never wrapped into another seed (issue 14).
TEST(ParseSeed, TakesEveryUnsignedValueAndRefusesSignsJunkAndOverflow) {
  EXPECT_EQ(ParseSeed("0").Value(), 0u);
  EXPECT_EQ(ParseSeed("1").Value(), 1u);
  EXPECT_EQ(ParseSeed("18446744073709551615").Value(), 18446744073709551615u);
  for (const char* bad :
       {"-1", "+1", "", " 1", "1e3", "0x10", "18446744073709551616", "99999999999999999999999"}) {
    auto seed = ParseSeed(bad);
    ASSERT_FALSE(seed) << bad;
    EXPECT_NE(seed.GetError().message.find(std::string("--seed \"") + bad + "\""), std::string::npos)
        << seed.GetError().message;
  }
  EXPECT_NE(ParseSeed("18446744073709551616").GetError().message.find("(too large)"), std::string::npos);
  EXPECT_NE(ParseSeed(std::string(100, '7')).GetError().message.find("..."), std::string::npos);
}

}  // namespace sat_check_test
}  // namespace talus::validation
