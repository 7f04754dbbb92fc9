// Stress envelopes (harness stress.h): the search finds a synthetic
// oracle's threshold by walking and bisecting, and one tiny stress axis
// runs end to end on the Talus backend with the outcome physics demands.
#include <gtest/gtest.h>

#include <cmath>

#include "talus/harness/stress/stress.h"
#include "talus/reference/talus_backend.h"

namespace talus::harness {
namespace stress_test {

std::function<EnvelopeProbe(double)> Below(double threshold, int* calls) {
  return [threshold, calls](double value) {
    ++*calls;
    EnvelopeProbe probe;
    probe.pass = value <= threshold;
    return probe;
  };
}

TEST(SearchEnvelope, BisectsAnIntegerAxisToAdjacentValues) {
  int calls = 0;
  const EnvelopeResult result = SearchEnvelope({2, 2, 256, true, 0}, Below(37, &calls));
  EXPECT_EQ(result.lastPass, 37.0);
  EXPECT_EQ(result.firstFail, 38.0);
  // Walk 2, 4, 8, 16, 32, 64 then bisect [32, 64]: 48, 40, 36, 38, 37.
  EXPECT_EQ(calls, 11);
  ASSERT_EQ(result.probes.size(), 11u);
  EXPECT_EQ(result.probes[5].value, 64.0);
  EXPECT_FALSE(result.probes[5].pass);
}

TEST(SearchEnvelope, BisectsARealAxisGeometrically) {
  int calls = 0;
  const EnvelopeResult result = SearchEnvelope({1, 10, 1e6, false, 4}, Below(3300.0, &calls));
  // Walk to 1e4 (fail), then 4 geometric midpoints: the bracket shrinks
  // from a factor 10 to 10^(1/16) and still holds the threshold.
  EXPECT_LE(result.lastPass, 3300.0);
  EXPECT_GT(result.firstFail, 3300.0);
  EXPECT_NEAR(result.firstFail / result.lastPass, std::pow(10.0, 1.0 / 16.0), 1e-9);
  EXPECT_EQ(calls, 5 + 4);
}

TEST(SearchEnvelope, ReportsAxesThatNeverOrAlwaysFail) {
  int calls = 0;
  const EnvelopeResult never = SearchEnvelope({1, 10, 100, false, 3}, Below(1e9, &calls));
  EXPECT_EQ(never.lastPass, 100.0);
  EXPECT_TRUE(std::isnan(never.firstFail));
  const EnvelopeResult always = SearchEnvelope({1, 10, 100, false, 3}, Below(0.5, &calls));
  EXPECT_TRUE(std::isnan(always.lastPass));
  EXPECT_EQ(always.firstFail, 1.0);
  // Walking down: values 1, 0.1, 0.01; passes while >= 0.05 here.
  const EnvelopeResult down = SearchEnvelope({1, 0.1, 0.01, false, 0}, [](double v) {
    EnvelopeProbe p;
    p.pass = v >= 0.05;
    return p;
  });
  EXPECT_NEAR(down.lastPass, 0.1, 1e-15);
  EXPECT_NEAR(down.firstFail, 0.01, 1e-15);
}

TEST(StressAxes, EveryAxisHasANameCriterionAndSaneSearches) {
  for (const StressAxisInfo& info : StressAxes()) {
    EXPECT_FALSE(info.name.empty());
    EXPECT_FALSE(info.criterion.empty()) << info.name;
    for (const EnvelopeSearch& s : {info.ci, info.full}) {
      EXPECT_GT(s.start, 0.0) << info.name;
      EXPECT_TRUE(s.factor > 1.0 ? s.limit >= s.start : s.limit <= s.start) << info.name;
    }
    EXPECT_FALSE(StressRuns(info.axis, info.ci.start).empty()) << info.name;
  }
}

const BackendRegistry& Registry() {
  static const BackendRegistry registry = [] {
    BackendRegistry r;
    reference::RegisterTalusBackends(r);
    return r;
  }();
  return registry;
}

TEST(StressSpeed, ASlowBoxStopsAtTheWallAndAFastOneTunnelsThroughAFixedMargin) {
  // At 1 m/s the box moves 1.7 cm per step against a 0.15 m overlap window:
  // it must be stopped. At 600 m/s it moves 10 m per step: with a fixed
  // 2 cm speculative margin (talus-writeup) the wall is never in a
  // manifold and the box must end beyond it; talus grows the margin to the
  // step's reach (MethodSettings::speculativeMotion), so the wall is a
  // speculative contact the step before and the box must end against it,
  // its centre 0.05 + 0.025 m from the wall's, to within 1 mm.
  for (const char* backend : {"talus", "talus-writeup"}) {
    const EnvelopeProbe slow = ProbeStress(Registry(), backend, StressAxis::Speed, 1.0);
    EXPECT_TRUE(slow.pass) << backend << ": " << slow.detail;
    EXPECT_LT(slow.measure, 0.0) << backend;
  }
  const EnvelopeProbe fixed = ProbeStress(Registry(), "talus-writeup", StressAxis::Speed, 600.0);
  EXPECT_FALSE(fixed.pass);
  EXPECT_NE(fixed.detail.find("tunnelled"), std::string::npos) << fixed.detail;
  const EnvelopeProbe reach = ProbeStress(Registry(), "talus", StressAxis::Speed, 600.0);
  EXPECT_TRUE(reach.pass) << reach.detail;
  EXPECT_NEAR(reach.measure, -0.075, 1e-3);
}

TEST(StressEnvelope, ATwoBoxColumnStandsEndToEnd) {
  const EnvelopeResult result = SearchEnvelope(
      {2, 2, 2, true, 0}, [](double v) { return ProbeStress(Registry(), "talus", StressAxis::Column, v); });
  EXPECT_EQ(result.lastPass, 2.0);
  const std::vector<StressEntry> entries{{"column", "talus", result}};
  const std::string markdown = StressMarkdown(entries);
  EXPECT_NE(markdown.find("| talus | 2 / - |"), std::string::npos) << markdown;
  EXPECT_NE(StressHtml(entries).find("<td>2 / -</td>"), std::string::npos);
}

}  // namespace stress_test
}  // namespace talus::harness
