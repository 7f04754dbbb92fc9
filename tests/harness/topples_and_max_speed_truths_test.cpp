// The truth kinds of the structure scenes (issue 25): topples (a row of
// dominoes falls, in order) and max_speed (overlapping bodies are pushed
// apart without being thrown; a pile is still at the end), each read from a
// scenario text: a hand-made trajectory that does what the truth says
// passes, one with the defect the truth is there to catch fails (a domino
// left standing, one falling before its neighbour, a body launched); the
// loader refuses a bad entry naming file and field; the writer's text
// reloads to the same truth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "talus/harness/scenario/scenario_loader.h"
#include "talus/harness/scenario/scenario_writer.h"
#include "talus/harness/truth/truth_check.h"

namespace talus::harness {
namespace topples_and_max_speed_truths_test {

// gtest's Test::Run hides harness::Run inside TEST bodies.
using ScenarioRun = Run;

constexpr double kStep = 0.01;  // s; 200 steps make the 2 s run
constexpr int kSteps = 200;
constexpr double kNever = std::numeric_limits<double>::infinity();  // a fall time: stays standing

// A 2 s run at 10 ms: a static ground (index 0) and three dominoes d0, d1,
// d2 (indices 1 to 3) standing 1 m apart along x, and one truth.
std::string Text(const std::string& truth) {
  return std::string(
             R"({"name": "row", "world": {"timeStep": 0.01, "iterations": 10, "duration": {"seconds": 2.0}},
    "bodies": [{"name": "ground", "shape": {"kind": "box", "halfExtents": [5, 0.5, 5]}, "motion": "static", "position": [0, -0.5, 0]},
      {"name": "d0", "shape": {"kind": "box", "halfExtents": [0.1, 0.5, 0.2]}, "motion": "dynamic", "position": [0, 0.5, 0], "mass": 1.0},
      {"name": "d1", "shape": {"kind": "box", "halfExtents": [0.1, 0.5, 0.2]}, "motion": "dynamic", "position": [1, 0.5, 0], "mass": 1.0},
      {"name": "d2", "shape": {"kind": "box", "halfExtents": [0.1, 0.5, 0.2]}, "motion": "dynamic", "position": [2, 0.5, 0], "mass": 1.0}],
    "truths": [)") +
         truth + "]}";
}

ScenarioRun Load(const std::string& truth) {
  auto runs = ParseScenarioText(Text(truth), "row.json");
  EXPECT_TRUE(runs) << runs.GetError().message;
  return runs ? runs.Value().front() : ScenarioRun{};
}

std::string Refusal(const std::string& truth) {
  auto runs = ParseScenarioText(Text(truth), "row.json");
  EXPECT_FALSE(runs) << truth << " was accepted";
  return runs ? std::string() : runs.GetError().message;
}

// Body states at every `stride`-th step (and the last) from state(body
// index, time).
Trajectory Track(const ScenarioRun& run, const std::function<BodyReading(std::size_t, double)>& state,
                 int stride = 1) {
  Trajectory trajectory;
  trajectory.timeStep = kStep;
  trajectory.stride = stride;
  for (int n = 0; n <= kSteps; ++n) {
    if (n % stride != 0 && n != kSteps) continue;
    Sample sample;
    sample.step = n;
    sample.time = n * kStep;
    for (std::size_t b = 0; b < run.scenario.bodies.size(); ++b) {
      BodyReading reading = state(b, sample.time);
      reading.mass = run.scenario.bodies[b].motion == Motion::Dynamic ? run.scenario.bodies[b].mass : 0.0;
      sample.bodies.push_back(reading);
    }
    trajectory.samples.push_back(sample);
  }
  return trajectory;
}

const MetricResult& Metric(const std::vector<MetricResult>& metrics, const std::string& name) {
  for (const MetricResult& metric : metrics) {
    if (metric.name == name) return metric;
  }
  ADD_FAILURE() << "no metric " << name;
  static const MetricResult none;
  return none;
}

void ExpectRoundTrip(const ScenarioRun& run) {
  auto again = ParseScenarioText(ScenarioToJson(run.scenario), "saved.json");
  ASSERT_TRUE(again) << again.GetError().message;
  const Truth& before = run.scenario.truths.front();
  const Truth& after = again.Value().front().scenario.truths.front();
  EXPECT_TRUE(before.kind == after.kind);
  EXPECT_EQ(before.tolerance, after.tolerance);
}

// Domino i (body i + 1) standing until fall[i] s, then turning about z at
// 2 rad/s up to pi/2 (a fall time of +infinity leaves it standing); its
// centre of mass stays put (the truth reads only the orientation).
BodyReading Domino(const ScenarioRun& run, std::size_t b, double t, const std::vector<double>& fall) {
  BodyReading reading;
  reading.centerOfMass = run.scenario.bodies[b].position;
  reading.origin = reading.centerOfMass;
  const double start = b == 0 ? kNever : fall[b - 1];
  const double angle = t <= start ? 0.0 : std::min(2.0 * (t - start), 0.5 * std::numbers::pi);
  reading.orientation = Quat(Eigen::AngleAxisd(-angle, Vec3::UnitZ()));
  return reading;
}

const std::string kTopples =
    R"({"kind": "topples", "bodies": ["d0", "d1", "d2"], "angle": 0.4, "within": 1.9,
        "tolerance": {"absolute": 0.01, "reason": "threshold precision"}})";

TEST(TopplesTruth, ARowFallingInOrderPassesAndAStandingOrEarlyDominoFails) {
  const ScenarioRun run = Load(kTopples);
  const Truth& truth = run.scenario.truths.front();
  const auto& kind = std::get<TopplesTruth>(truth.kind);
  EXPECT_EQ(kind.bodies, (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(kind.within, 1.9);
  // In order, 0.3 s apart: each reaches 0.4 rad 0.2 s after it starts.
  for (const int stride : {1, 7}) {
    const auto inOrder = [&](std::size_t b, double t) { return Domino(run, b, t, {0.1, 0.4, 0.7}); };
    const auto metrics = EvaluateTruth(run, truth, Track(run, inOrder, stride));
    ASSERT_EQ(metrics.size(), 2u);
    EXPECT_TRUE(Metric(metrics, "topples.shortfall").pass) << stride;
    EXPECT_EQ(Metric(metrics, "topples.shortfall").measured, 0.0);
    EXPECT_TRUE(Metric(metrics, "topples.order").pass) << stride;
    EXPECT_EQ(Metric(metrics, "topples.order").measured, 0.0);
  }
  // The middle domino stays standing (the chain stops there): d1 falls
  // 0.4 rad short, and d2 never falls either.
  const auto stops = [&](std::size_t b, double t) { return Domino(run, b, t, {0.1, kNever, kNever}); };
  auto metrics = EvaluateTruth(run, truth, Track(run, stops));
  EXPECT_FALSE(Metric(metrics, "topples.shortfall").pass);
  EXPECT_NEAR(Metric(metrics, "topples.shortfall").measured, 0.4, 1e-12);
  EXPECT_TRUE(Metric(metrics, "topples.order").pass);  // nothing fell out of turn
  // The last domino falls first, at 0.05 s: when it has toppled (0.25 s,
  // at 0.39 rad), d1 has not started (0.4 rad short).
  const auto early = [&](std::size_t b, double t) { return Domino(run, b, t, {0.1, 0.4, 0.05}); };
  metrics = EvaluateTruth(run, truth, Track(run, early));
  EXPECT_TRUE(Metric(metrics, "topples.shortfall").pass);
  EXPECT_FALSE(Metric(metrics, "topples.order").pass);
  EXPECT_NEAR(Metric(metrics, "topples.order").measured, 0.4, 1e-12);
  // Falling after `within` counts as standing: d2 starts at 1.8 s and has
  // turned 0.2 rad by 1.9 s.
  const auto late = [&](std::size_t b, double t) { return Domino(run, b, t, {0.1, 0.4, 1.8}); };
  metrics = EvaluateTruth(run, truth, Track(run, late));
  EXPECT_FALSE(Metric(metrics, "topples.shortfall").pass);
  EXPECT_NEAR(Metric(metrics, "topples.shortfall").measured, 0.2, 1e-9);
  ExpectRoundTrip(run);
}

TEST(TopplesTruth, TheLoaderRefusesABadEntryNamingTheField) {
  EXPECT_EQ(Refusal(R"({"kind": "topples", "bodies": ["d0", "d1"], "angle": 0.01,
      "tolerance": {"absolute": 0.01, "reason": "r"}})"),
            "row.json: /truths/0/tolerance/absolute: 0.01 rad is not below the angle (0.01 rad): every body "
            "would count as toppled where it starts");
  EXPECT_EQ(Refusal(R"({"kind": "topples", "bodies": ["d0", "ground"], "angle": 0.4,
      "tolerance": {"absolute": 0.01, "reason": "r"}})"),
            "row.json: /truths/0/bodies/1: body \"ground\" is static");
  EXPECT_EQ(Refusal(R"({"kind": "topples", "bodies": ["d0", "d1"], "angle": 0.4, "within": 3,
      "tolerance": {"absolute": 0.01, "reason": "r"}})"),
            "row.json: /truths/0/within: 3 s is after the end of the run (the run ends at 2 s)");
  EXPECT_EQ(Refusal(R"({"kind": "topples", "bodies": ["d0", "d1"], "angle": 0.4,
      "tolerance": {"relative": 0.01, "reason": "r"}})"),
            "row.json: /truths/0/tolerance/absolute: is required (radians): the truth is 0, so a relative "
            "tolerance alone allows nothing");
  EXPECT_NE(Refusal(R"({"kind": "topples", "bodies": ["d0"], "angle": 0.4,
      "tolerance": {"absolute": 0.01, "reason": "r"}})"),
            "");
  EXPECT_NE(Refusal(R"({"kind": "topples", "bodies": ["d0", "d1"], "angle": 4,
      "tolerance": {"absolute": 0.01, "reason": "r"}})"),
            "");
}

// d0 moving at `speed(t)` along x, the others still.
Trajectory Moving(const ScenarioRun& run, const std::function<double(double)>& speed, int stride = 1) {
  return Track(
      run,
      [&](std::size_t b, double t) {
        BodyReading reading;
        reading.centerOfMass = run.scenario.bodies[b].position;
        reading.origin = reading.centerOfMass;
        reading.orientation = run.scenario.bodies[b].orientation;
        if (b == 1) reading.linearVelocity = Vec3(speed(t), 0, 0);
        return reading;
      },
      stride);
}

TEST(MaxSpeedTruth, AGentlePushOutPassesAndALaunchOrJitterFails) {
  const ScenarioRun run =
      Load(R"({"kind": "max_speed", "tolerance": {"absolute": 2.0, "reason": "push-out"}})");
  const Truth& truth = run.scenario.truths.front();
  const auto& kind = std::get<MaxSpeedTruth>(truth.kind);
  EXPECT_EQ(kind.bodies, (std::vector<int>{1, 2, 3}));  // every dynamic body by default
  EXPECT_EQ(kind.from, 0.0);
  EXPECT_EQ(kind.until, 2.0);
  // Pushed out at up to 1.5 m/s over the first half second, then still.
  const auto gentle = [](double t) { return t < 0.5 ? 12.0 * t * (1.0 - 2.0 * t) : 0.0; };
  for (const int stride : {1, 7}) {
    const auto metrics = EvaluateTruth(run, truth, Moving(run, gentle, stride));
    ASSERT_EQ(metrics.size(), 1u);
    EXPECT_EQ(metrics[0].name, "max_speed.0s_to_2s");
    EXPECT_TRUE(metrics[0].pass) << stride;
    EXPECT_LE(metrics[0].measured, 1.5);
  }
  // Launched at 5 m/s for one step at 0.73 s.
  const auto launched = [](double t) { return std::abs(t - 0.73) < 1e-9 ? 5.0 : 0.0; };
  auto metrics = EvaluateTruth(run, truth, Moving(run, launched));
  EXPECT_FALSE(metrics[0].pass);
  EXPECT_EQ(metrics[0].measured, 5.0);
  ExpectRoundTrip(run);

  // The rest at the end: a window bounds only its own samples.
  const ScenarioRun rest = Load(R"({"kind": "max_speed", "bodies": ["d0"], "from": 1.5,
      "tolerance": {"absolute": 0.1, "reason": "one step of gravity"}})");
  const Truth& still = rest.scenario.truths.front();
  metrics = EvaluateTruth(rest, still, Moving(rest, launched));  // before the window
  EXPECT_EQ(metrics[0].name, "max_speed.1.5s_to_2s");
  EXPECT_TRUE(metrics[0].pass);
  EXPECT_EQ(metrics[0].measured, 0.0);
  const auto jitters = [](double t) { return t > 1.8 ? 0.3 * std::sin(100.0 * t) : 0.0; };
  metrics = EvaluateTruth(rest, still, Moving(rest, jitters));
  EXPECT_FALSE(metrics[0].pass);
  EXPECT_GT(metrics[0].measured, 0.2);
  ExpectRoundTrip(rest);
}

TEST(MaxSpeedTruth, TheLoaderRefusesABadEntryNamingTheField) {
  EXPECT_EQ(
      Refusal(R"({"kind": "max_speed", "bodies": ["ground"], "tolerance": {"absolute": 1, "reason": "r"}})"),
      "row.json: /truths/0/bodies/0: body \"ground\" is static");
  EXPECT_EQ(Refusal(R"({"kind": "max_speed", "from": 2, "tolerance": {"absolute": 1, "reason": "r"}})"),
            "row.json: /truths/0/from: 2 s is not before the end of the run (the run ends at 2 s)");
  EXPECT_EQ(Refusal(R"({"kind": "max_speed", "tolerance": {"relative": 1, "reason": "r"}})"),
            "row.json: /truths/0/tolerance/absolute: is required (m/s): the truth is 0, so a relative "
            "tolerance alone allows nothing");
  EXPECT_EQ(
      Refusal(
          R"({"kind": "max_speed", "bodies": ["d0", "d0"], "tolerance": {"absolute": 1, "reason": "r"}})"),
      "row.json: /truths/0/bodies/1: body \"d0\" is listed twice");
}

}  // namespace topples_and_max_speed_truths_test
}  // namespace talus::harness
