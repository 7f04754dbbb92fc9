// Perturbed repeats of the reference scenes (bench_perturb.h): the offsets
// stay inside their bound, the same seed gives the same scene and the same
// figures bit for bit, different seeds give different offsets, bad amounts
// and repeat counts are refused, and a series is summarized with its spread
// and whether the verdict held in every repeat. Plus the talus-scenes
// options (--perturb, --repeats, --perturb-seed) and their refusals.
#include "talus/harness/scenes/bench_perturb.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "support/command_outcome.h"
#include "talus/harness/scenes/bench_report_json.h"
#include "talus/harness/support/split_mix64.h"
#include "talus/reference/all_backends.h"

namespace talus::harness {
namespace bench_perturb_test {

constexpr double kProbe = 1e-9;  // issue 12's perturbation, metres

Scenario SmallPyramid() {
  auto built = MakePyramidScene(4);
  EXPECT_TRUE(built.Ok());
  return built.Value();
}

Scenario Perturbed(double amount, std::uint64_t seed) {
  auto perturbed = PerturbDynamicPositions(SmallPyramid(), amount, seed);
  EXPECT_TRUE(perturbed.Ok()) << perturbed.GetError().message;
  return perturbed.Value();
}

TEST(PerturbDynamicPositions, EveryDynamicBodyMovesWithinTheBoundAndStaticsStay) {
  const Scenario original = SmallPyramid();
  for (std::uint64_t seed : {0ull, 1ull, 20261124ull, ~0ull}) {
    const Scenario moved = Perturbed(kProbe, seed);
    ASSERT_EQ(moved.bodies.size(), original.bodies.size());
    int movedAxes = 0;
    for (size_t b = 0; b < moved.bodies.size(); ++b) {
      const BodySpec& before = original.bodies[b];
      const BodySpec& after = moved.bodies[b];
      if (before.motion != Motion::Dynamic) {
        EXPECT_EQ(after.position, before.position) << "static body " << b;
        continue;
      }
      for (int axis = 0; axis < 3; ++axis) {
        // The sum rounds to the coordinate's ulp (|x| <= 8 m here: 1.8e-15 m).
        const double roundOff =
            4.0 * std::numeric_limits<double>::epsilon() * std::abs(before.position[axis]);
        const double offset = after.position[axis] - before.position[axis];
        EXPECT_LE(std::abs(offset), kProbe + roundOff) << "body " << b << " axis " << axis;
        if (offset != 0.0) ++movedAxes;
      }
      EXPECT_EQ(after.orientation.coeffs(), before.orientation.coeffs());
      EXPECT_EQ(after.linearVelocity, before.linearVelocity);
    }
    // A uniform draw lands within round-off of 0 with probability ~1e-6 per axis.
    EXPECT_EQ(movedAxes, 3 * PyramidCubeCount(4)) << "seed " << seed;
  }
}

TEST(PerturbDynamicPositions, OffsetsAreTheSeededStreamInBodyOrder) {
  // The definition, written out: x, y, z of each dynamic body in turn.
  const Scenario original = SmallPyramid();
  const Scenario moved = Perturbed(kProbe, 42);
  SplitMix64 stream(42);
  for (size_t b = 0; b < original.bodies.size(); ++b) {
    if (original.bodies[b].motion != Motion::Dynamic) continue;
    for (int axis = 0; axis < 3; ++axis) {
      const double expected = original.bodies[b].position[axis] + kProbe * (2.0 * stream.NextUniform() - 1.0);
      EXPECT_EQ(moved.bodies[b].position[axis], expected) << "body " << b << " axis " << axis;
    }
  }
}

TEST(PerturbDynamicPositions, SameSeedSameSceneDifferentSeedsDifferentOffsets) {
  const Scenario first = Perturbed(kProbe, 7);
  const Scenario again = Perturbed(kProbe, 7);
  const Scenario other = Perturbed(kProbe, 8);
  int differing = 0;
  for (size_t b = 0; b < first.bodies.size(); ++b) {
    EXPECT_EQ(first.bodies[b].position, again.bodies[b].position) << b;
    for (int axis = 0; axis < 3; ++axis) {
      if (first.bodies[b].position[axis] != other.bodies[b].position[axis]) ++differing;
    }
  }
  // Neighbouring seeds are independent streams: every offset differs.
  EXPECT_EQ(differing, 3 * PyramidCubeCount(4));
}

TEST(PerturbDynamicPositions, ZeroAmountLeavesTheSceneBitForBit) {
  const Scenario original = SmallPyramid();
  const Scenario same = Perturbed(0.0, 99);
  for (size_t b = 0; b < original.bodies.size(); ++b) {
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_EQ(std::signbit(same.bodies[b].position[axis]), std::signbit(original.bodies[b].position[axis]));
      EXPECT_EQ(same.bodies[b].position[axis], original.bodies[b].position[axis]);
    }
  }
}

TEST(PerturbDynamicPositions, BadAmountsAreErrorsNamingTheValue) {
  for (double amount : {-1e-9, std::nan(""), std::numeric_limits<double>::infinity(), 2e-3}) {
    const auto result = PerturbDynamicPositions(SmallPyramid(), amount, 0);
    ASSERT_FALSE(result.Ok()) << amount;
    EXPECT_NE(result.GetError().message.find("perturbation"), std::string::npos) << result.GetError().message;
  }
  EXPECT_FALSE(PositionPerturbationProblem(kMaxPositionPerturbation).has_value());
  EXPECT_FALSE(PositionPerturbationProblem(0.0).has_value());
}

TEST(BenchRepeats, CountOutsideOneToTheMaximumIsRefused) {
  EXPECT_TRUE(BenchRepeatsProblem(0).has_value());
  EXPECT_TRUE(BenchRepeatsProblem(-1).has_value());
  EXPECT_TRUE(BenchRepeatsProblem(kMaxBenchRepeats + 1).has_value());
  EXPECT_FALSE(BenchRepeatsProblem(1).has_value());
  EXPECT_FALSE(BenchRepeatsProblem(kMaxBenchRepeats).has_value());
}

TEST(BenchRepeats, RepeatSeedIsSeedPlusRepeatModuloTwoToThe64) {
  EXPECT_EQ(RepeatSeed(10, 0), 10u);
  EXPECT_EQ(RepeatSeed(10, 9), 19u);
  EXPECT_EQ(RepeatSeed(~0ull, 1), 0u);
}

// Two runs of the same perturbed pyramid (H = 2, 5 cubes: small enough for
// the sanitizer pass) through Talus and both peers: same seed, same figures
// bit for bit; the report carries the perturbation. 130 steps: past the
// drift start (120), so the drift is measured over 10 steps.
TEST(BenchRepeats, SameSeedGivesTheSameFiguresOnEveryEngine) {
  const BackendRegistry& registry = reference::AllBackends();
  const BenchScene& pyramid = *FindBenchScene("pyramid");
  const BenchPerturbation perturbation{3, kProbe, RepeatSeed(5, 3)};
  for (const char* engine : {"talus", "bullet", "ode-quickstep"}) {
    auto first = RunBenchScene(registry, engine, pyramid, 2, 130, {}, perturbation);
    auto second = RunBenchScene(registry, engine, pyramid, 2, 130, {}, perturbation);
    ASSERT_TRUE(first.Ok() && second.Ok()) << engine;
    ASSERT_TRUE(first.Value().perturbation.has_value());
    EXPECT_EQ(first.Value().perturbation->seed, 8u);
    EXPECT_EQ(first.Value().perturbation->repeat, 3);
    ASSERT_TRUE(first.Value().drift.has_value());
    EXPECT_EQ(*first.Value().drift, *second.Value().drift) << engine;
    EXPECT_EQ(first.Value().maxContacts, second.Value().maxContacts) << engine;
  }
  auto bad = RunBenchScene(registry, "talus", pyramid, 2, 130, {}, BenchPerturbation{0, -1.0, 0});
  EXPECT_FALSE(bad.Ok());
}

BenchReport PyramidRun(double drift) {
  BenchReport report;
  report.engine = "talus";
  report.scene = "pyramid";
  report.parameter = 15;
  report.drift = drift;
  return report;
}

TEST(SummarizeRepeats, SpreadAndVerdictOfASeries) {
  // Odd count: the median is the middle value; all under 5 mm: same verdict.
  auto held = SummarizeRepeats({PyramidRun(0.003), PyramidRun(0.001), PyramidRun(0.002)});
  ASSERT_TRUE(held.Ok());
  EXPECT_EQ(held.Value().runs, 3);
  EXPECT_EQ(held.Value().min, 0.001);
  EXPECT_EQ(held.Value().median, 0.002);
  EXPECT_EQ(held.Value().max, 0.003);
  EXPECT_EQ(held.Value().verdictsHeld, 3);
  EXPECT_TRUE(held.Value().sameVerdict);

  // The issue's lottery: 1.5 mm in one run, 1.2 cm in another.
  auto lottery = SummarizeRepeats({PyramidRun(0.0015), PyramidRun(0.012)});
  ASSERT_TRUE(lottery.Ok());
  EXPECT_DOUBLE_EQ(lottery.Value().median, 0.5 * (0.0015 + 0.012));
  EXPECT_EQ(lottery.Value().verdictsHeld, 1);
  EXPECT_FALSE(lottery.Value().sameVerdict);
  const std::string line = FormatRepeatSummary(PyramidRun(0.0015), lottery.Value());
  EXPECT_NE(line.find("held in 1 of 2"), std::string::npos) << line;
  EXPECT_NE(line.find("DIFFERS"), std::string::npos) << line;

  // All failing is the same verdict too; a NaN drift fails and poisons the spread.
  auto failed = SummarizeRepeats({PyramidRun(0.02), PyramidRun(std::nan(""))});
  ASSERT_TRUE(failed.Ok());
  EXPECT_EQ(failed.Value().verdictsHeld, 0);
  EXPECT_TRUE(failed.Value().sameVerdict);
  EXPECT_TRUE(std::isnan(failed.Value().max));
}

// The one median of a time: across repeated runs, of each run's total.
// Three runs of 9, 7 and 30 s (the last a busy machine): the median is 9 s,
// and the line says it beside the spread.
TEST(SummarizeRepeats, TheCostIsTheMedianOfTheRunsTotals) {
  std::vector<BenchReport> runs = {PyramidRun(0.001), PyramidRun(0.002), PyramidRun(0.003)};
  runs[0].totalMs = 9000.0;
  runs[1].totalMs = 7000.0;
  runs[2].totalMs = 30000.0;
  auto summary = SummarizeRepeats(runs);
  ASSERT_TRUE(summary.Ok());
  EXPECT_EQ(summary.Value().totalMsMin, 7000.0);
  EXPECT_EQ(summary.Value().totalMsMedian, 9000.0);
  EXPECT_EQ(summary.Value().totalMsMax, 30000.0);
  const std::string line = FormatRepeatSummary(runs[0], summary.Value());
  EXPECT_NE(line.find("; total ms min 7000 median 9000 max 30000"), std::string::npos) << line;
  // An even count: the mean of the middle two.
  runs.pop_back();
  EXPECT_EQ(SummarizeRepeats(runs).Value().totalMsMedian, 8000.0);
}

TEST(SummarizeRepeats, HullPileVerdictIsNothingEscapedAndSkippedRunsAreLeftOut) {
  BenchReport inside;
  inside.scene = "hull_pile";
  inside.maxPenetration = 0.01;
  inside.escaped = 0;
  BenchReport escaped = inside;
  escaped.maxPenetration = 0.02;
  escaped.escaped = 1;
  BenchReport skipped = inside;
  skipped.skipped = "too many bodies";
  auto summary = SummarizeRepeats({inside, escaped, skipped});
  ASSERT_TRUE(summary.Ok());
  EXPECT_EQ(summary.Value().runs, 2);
  EXPECT_EQ(summary.Value().max, 0.02);
  EXPECT_FALSE(summary.Value().sameVerdict);
  EXPECT_FALSE(SummarizeRepeats({skipped}).Ok());
  EXPECT_FALSE(SummarizeRepeats({}).Ok());
}

TEST(BenchRepeats, PerturbedJsonLinesCarryTheRepeatAndReadBackAsPlainReports) {
  BenchReport report = PyramidRun(0.001);
  report.bodies = 1240;
  report.steps = 600;
  report.perturbation = BenchPerturbation{2, kProbe, 12};
  const std::string line = BenchReportToJson(report);
  EXPECT_NE(line.find(R"("repeat":2,"perturb_m":1e-09,"perturb_seed":12)"), std::string::npos) << line;
  auto read = ParseBenchReportLines(line, "test");
  ASSERT_TRUE(read.Ok()) << read.GetError().message;
  ASSERT_EQ(read.Value().size(), 1u);
  EXPECT_EQ(read.Value()[0].drift, report.drift);
  EXPECT_FALSE(read.Value()[0].perturbation.has_value());  // not read back (bench_report_json.h)
}

#ifdef TALUS_SCENES_BINARY
using Outcome = testing_support::CommandOutcome;

Outcome Execute(const std::string& arguments) {
  return testing_support::RunCommand(std::string(TALUS_SCENES_BINARY) + " " + arguments);
}

TEST(ScenesCommandPerturb, BadPerturbationsRepeatsAndSeedsAreRefusedNamingTheOption) {
  const std::string base = "--scene pyramid --param 2 --steps 1 --engines talus ";
  for (const char* bad : {"--perturb -1e-9", "--perturb nan", "--perturb inf", "--perturb 0.01"}) {
    const Outcome outcome = Execute(base + bad);
    EXPECT_EQ(outcome.code, 2) << bad << ": " << outcome.output;
    EXPECT_NE(outcome.output.find("--perturb: perturbation"), std::string::npos)
        << bad << ": " << outcome.output;
  }
  for (const char* bad : {"--perturb 1e-9 --repeats 0", "--perturb 1e-9 --repeats 1001"}) {
    const Outcome outcome = Execute(base + bad);
    EXPECT_EQ(outcome.code, 2) << bad << ": " << outcome.output;
    EXPECT_NE(outcome.output.find("--repeats: repeats"), std::string::npos) << bad << ": " << outcome.output;
  }
  for (const char* bad : {"--repeats 3", "--perturb-seed 4"}) {
    const Outcome outcome = Execute(base + bad);
    EXPECT_EQ(outcome.code, 2) << bad << ": " << outcome.output;
    EXPECT_NE(outcome.output.find("need --perturb"), std::string::npos) << bad << ": " << outcome.output;
  }
  const Outcome negativeSeed = Execute(base + "--perturb 1e-9 --perturb-seed -1");
  EXPECT_NE(negativeSeed.code, 0) << negativeSeed.output;
  EXPECT_NE(negativeSeed.output.find("--perturb-seed"), std::string::npos) << negativeSeed.output;
}

TEST(ScenesCommandPerturb, RepeatsPrintOneLineEachAndTheSpread) {
  // Repeat 1 of seed 10 is the run of seed 11 alone: same drift, same line
  // but for the repeat index.
  const Outcome series = Execute(
      "--scene pyramid --param 2 --steps 125 --engines talus --perturb 1e-9 "
      "--repeats 2 --perturb-seed 10");
  ASSERT_EQ(series.code, 0) << series.output;
  EXPECT_NE(series.output.find("repeat,perturb_m,perturb_seed"), std::string::npos) << series.output;
  EXPECT_NE(series.output.find("drift_m over 2 repeats"), std::string::npos) << series.output;
  const Outcome alone =
      Execute("--scene pyramid --param 2 --steps 125 --engines talus --perturb 1e-9 --perturb-seed 11");
  ASSERT_EQ(alone.code, 0) << alone.output;
  // The drift is the 13th column (index 12); times (8, 9, 10) differ between runs.
  auto driftOf = [](const std::string& output, const std::string& suffix) {
    const size_t end = output.find(suffix);
    if (end == std::string::npos) return std::string("missing");
    const size_t begin = output.rfind('\n', end) + 1;
    std::string line = output.substr(begin, end - begin);
    for (int column = 0; column < 12; ++column) line = line.substr(line.find(',') + 1);
    return line.substr(0, line.find(','));
  };
  EXPECT_EQ(driftOf(series.output, ",1,1.0000000000000001e-09,11"),
            driftOf(alone.output, ",0,1.0000000000000001e-09,11"));
  EXPECT_NE(driftOf(alone.output, ",0,1.0000000000000001e-09,11"), "missing") << alone.output;
}
#endif

}  // namespace bench_perturb_test
}  // namespace talus::harness
