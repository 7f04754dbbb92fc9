// The generic truth kinds (at_rest, moves, state_at, energy_not_increasing,
// momentum_conserved, max_penetration), each read from a scenario text: a
// hand-made trajectory that does what the truth says passes, one with the
// defect the truth is there to catch (what a broken engine would do) fails;
// the loader refuses a bad entry naming file and field; the writer's text
// reloads to the same truth.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "talus/harness/scenario/scenario_loader.h"
#include "talus/harness/scenario/scenario_writer.h"
#include "talus/harness/truth/truth_check.h"

namespace talus::harness {
namespace generic_truths_test {

// gtest's Test::Run hides harness::Run inside TEST bodies.
using ScenarioRun = Run;

constexpr double kStep = 0.01;  // s; 100 steps make the 1 s run
constexpr int kSteps = 100;
constexpr double kG = 9.81;

// A 1 s run at 10 ms: a static ground (index 0, left out when `free`, which
// also turns gravity off), a 2 kg sphere "a" at (0, 1, 0) and a 3 kg box "b"
// at (1, 1, 0) (indices 1 and 2, or 0 and 1 when free), and one truth.
std::string Text(const std::string& truth, bool free = false) {
  const std::string ground =
      R"({"name": "ground", "shape": {"kind": "box", "halfExtents": [5, 0.5, 5]}, "motion": "static", "position": [0, -0.5, 0]},)";
  return std::string(
             R"({"name": "generic", "world": {"timeStep": 0.01, "iterations": 10, "duration": {"seconds": 1.0})") +
         (free ? R"(, "gravity": [0, 0, 0]})" : "}") + R"(, "bodies": [)" + (free ? "" : ground) +
         R"({"name": "a", "shape": {"kind": "sphere", "radius": 0.1}, "motion": "dynamic", "position": [0, 1, 0], "mass": 2.0},
      {"name": "b", "shape": {"kind": "box", "halfExtents": [0.1, 0.1, 0.1]}, "motion": "dynamic", "position": [1, 1, 0], "mass": 3.0}],
    "truths": [)" +
         truth + "]}";
}

ScenarioRun Load(const std::string& truth, bool free = false) {
  auto runs = ParseScenarioText(Text(truth, free), "generic.json");
  EXPECT_TRUE(runs) << runs.GetError().message;
  return runs ? runs.Value().front() : ScenarioRun{};
}

std::string Refusal(const std::string& truth, bool free = false) {
  auto runs = ParseScenarioText(Text(truth, free), "generic.json");
  EXPECT_FALSE(runs) << truth << " was accepted";
  return runs ? std::string() : runs.GetError().message;
}

// Body states at every `stride`-th step (and the last) from state(body
// index, time); masses from the run's bodies, static bodies massless.
Trajectory Track(const ScenarioRun& run, const std::function<BodyReading(std::size_t, double)>& state,
                 int stride = 1, const std::function<double(double)>& depth = nullptr) {
  Trajectory trajectory;
  trajectory.timeStep = kStep;
  trajectory.stride = stride;
  for (int n = 0; n <= kSteps; ++n) {
    if (n % stride != 0 && n != kSteps) continue;
    Sample sample;
    sample.step = n;
    sample.time = n * kStep;
    for (std::size_t b = 0; b < run.scenario.bodies.size(); ++b) {
      const BodySpec& spec = run.scenario.bodies[b];
      BodyReading reading = state(b, sample.time);
      reading.mass = spec.motion == Motion::Dynamic ? spec.mass : 0.0;
      sample.bodies.push_back(reading);
    }
    if (depth) sample.maxPenetration = depth(sample.time);
    trajectory.samples.push_back(sample);
  }
  return trajectory;
}

// Every body where the file put it, still.
BodyReading Still(const ScenarioRun& run, std::size_t b) {
  BodyReading reading;
  reading.centerOfMass = run.scenario.bodies[b].position;
  reading.origin = reading.centerOfMass;
  reading.orientation = run.scenario.bodies[b].orientation;
  return reading;
}

const MetricResult& Metric(const std::vector<MetricResult>& metrics, const std::string& name) {
  for (const MetricResult& metric : metrics) {
    if (metric.name == name) return metric;
  }
  ADD_FAILURE() << "no metric " << name;
  static const MetricResult none;
  return none;
}

// The writer's text loads back to the same truth (kind, bounds' reasons).
void ExpectRoundTrip(const ScenarioRun& run) {
  auto again = ParseScenarioText(ScenarioToJson(run.scenario), "saved.json");
  ASSERT_TRUE(again) << again.GetError().message;
  const Truth& before = run.scenario.truths.front();
  const Truth& after = again.Value().front().scenario.truths.front();
  EXPECT_TRUE(before.kind == after.kind);
  EXPECT_EQ(before.boundReasons, after.boundReasons);
  EXPECT_EQ(before.tolerance, after.tolerance);
}

const std::string kAtRest =
    R"({"kind": "at_rest", "bodies": ["a", "b"], "from": 0.5,
        "maxTilt": {"value": 0.01, "reason": "tilt"}, "maxSpeed": {"value": 0.01, "reason": "speed"},
        "tolerance": {"absolute": 0.001, "reason": "drift"}})";

TEST(AtRestTruth, StillBodiesPassAndSlidingTiltingOrJitteringOnesFail) {
  const ScenarioRun run = Load(kAtRest);
  const Truth& truth = run.scenario.truths.front();
  EXPECT_EQ(std::get<AtRestTruth>(truth.kind).until,
            1.0);  // the run's end by default
  const auto still = [&](std::size_t b, double) { return Still(run, b); };
  for (const MetricResult& metric : EvaluateTruth(run, truth, Track(run, still, 3))) {
    EXPECT_TRUE(metric.pass) << metric.name;
    EXPECT_EQ(metric.measured, 0.0) << metric.name;
  }
  // b slides 5 mm at 0.8 s: drifted 5 times the 1 mm allowed.
  const auto slides = [&](std::size_t b, double t) {
    BodyReading reading = Still(run, b);
    if (b == 2 && t >= 0.8) reading.centerOfMass.x() += 0.005;
    return reading;
  };
  auto metrics = EvaluateTruth(run, truth, Track(run, slides));
  EXPECT_FALSE(Metric(metrics, "at_rest.drift.a,b").pass);
  EXPECT_NEAR(Metric(metrics, "at_rest.drift.a,b").measured, 0.005, 1e-15);
  // a tips 0.05 rad about z in place: within the drift, past maxTilt.
  const auto tips = [&](std::size_t b, double t) {
    BodyReading reading = Still(run, b);
    if (b == 1 && t >= 0.9) reading.orientation = Quat(Eigen::AngleAxisd(0.05, Vec3::UnitZ()));
    return reading;
  };
  metrics = EvaluateTruth(run, truth, Track(run, tips));
  EXPECT_TRUE(Metric(metrics, "at_rest.drift.a,b").pass);
  EXPECT_FALSE(Metric(metrics, "at_rest.tilt.a,b").pass);
  EXPECT_NEAR(Metric(metrics, "at_rest.tilt.a,b").measured, 0.05, 1e-12);
  EXPECT_EQ(Metric(metrics, "at_rest.tilt.a,b").reason, "tilt");
  // b buzzes in place at 0.1 m/s: no drift at the samples, but not at rest.
  const auto buzzes = [&](std::size_t b, double t) {
    BodyReading reading = Still(run, b);
    if (b == 2 && t >= 0.5) reading.linearVelocity = Vec3(0, std::fmod(t * 100.0, 2.0) < 1.0 ? 0.1 : -0.1, 0);
    return reading;
  };
  metrics = EvaluateTruth(run, truth, Track(run, buzzes));
  EXPECT_TRUE(Metric(metrics, "at_rest.drift.a,b").pass);
  EXPECT_FALSE(Metric(metrics, "at_rest.speed.a,b").pass);
  // Before the window (from 0.5 s) the bodies may still settle.
  const auto settles = [&](std::size_t b, double t) {
    BodyReading reading = Still(run, b);
    if (b == 2 && t < 0.3) reading.linearVelocity = Vec3(0, -1.0, 0);
    return reading;
  };
  EXPECT_TRUE(Metric(EvaluateTruth(run, truth, Track(run, settles)), "at_rest.speed.a,b").pass);
  ExpectRoundTrip(run);
}

TEST(AtRestTruth, TwoTruthsOfOneSceneReportUnderTheirOwnBodies) {
  // A layer each with its own allowance (a load stands on more contacts
  // than its supports): one name per truth, each judged by its own bound.
  const std::string a = R"({"kind": "at_rest", "bodies": ["a"],
        "maxTilt": {"value": 0.01, "reason": "tilt"}, "maxSpeed": {"value": 1, "reason": "speed"},
        "tolerance": {"absolute": 0.001, "reason": "a's drift"}})";
  const std::string b = R"({"kind": "at_rest", "bodies": ["b"],
        "maxTilt": {"value": 0.01, "reason": "tilt"}, "maxSpeed": {"value": 1, "reason": "speed"},
        "tolerance": {"absolute": 0.01, "reason": "b's drift"}})";
  const ScenarioRun run = Load(a + ", " + b);
  // Both sink 5 mm: inside b's 1 cm, outside a's 1 mm.
  const auto sink = [&](std::size_t body, double t) {
    BodyReading reading = Still(run, body);
    if (body != 0 && t >= 0.5) reading.centerOfMass.y() -= 0.005;
    return reading;
  };
  const Trajectory trajectory = Track(run, sink);
  const auto first = EvaluateTruth(run, run.scenario.truths[0], trajectory);
  const auto second = EvaluateTruth(run, run.scenario.truths[1], trajectory);
  EXPECT_FALSE(Metric(first, "at_rest.drift.a").pass);
  EXPECT_TRUE(Metric(second, "at_rest.drift.b").pass);
}

TEST(AtRestTruth, ManyBodiesAreNamedByTheFirstTwoAndACount) {
  const std::string four = R"({"kind": "at_rest", "bodies": ["a", "b", "c", "d"],
        "maxTilt": {"value": 0.01, "reason": "tilt"}, "maxSpeed": {"value": 1, "reason": "speed"},
        "tolerance": {"absolute": 0.001, "reason": "drift"}})";
  std::string text = Text(four);
  const std::string extra =
      R"({"name": "c", "shape": {"kind": "sphere", "radius": 0.1}, "motion": "dynamic", "position": [2, 1, 0], "mass": 1.0},
      {"name": "d", "shape": {"kind": "sphere", "radius": 0.1}, "motion": "dynamic", "position": [3, 1, 0], "mass": 1.0}],)";
  text.replace(text.find("}],"), 3, "}, " + extra);
  auto runs = ParseScenarioText(text, "generic.json");
  ASSERT_TRUE(runs) << runs.GetError().message;
  const ScenarioRun& run = runs.Value().front();
  const auto still = [&](std::size_t body, double) { return Still(run, body); };
  const auto metrics = EvaluateTruth(run, run.scenario.truths[0], Track(run, still));
  EXPECT_TRUE(Metric(metrics, "at_rest.drift.a,b,+2").pass);
}

TEST(AtRestTruth, LoaderRefusesWhatCannotBeJudged) {
  const auto with = [](const std::string& from, const std::string& to) {
    std::string text = kAtRest;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  EXPECT_EQ(Refusal(with("\"b\"]", "\"c\"]")), "generic.json: /truths/0/bodies/1: no body named \"c\"");
  EXPECT_EQ(Refusal(with("\"b\"]", "\"ground\"]")),
            "generic.json: /truths/0/bodies/1: body \"ground\" is static");
  EXPECT_EQ(Refusal(with("\"b\"]", "\"a\"]")),
            "generic.json: /truths/0/bodies/1: body \"a\" is listed twice");
  EXPECT_EQ(Refusal(with("\"from\": 0.5", "\"until\": 2")),
            "generic.json: /truths/0/until: 2 s is after the end of the run "
            "(the run ends at 1 s)");
  EXPECT_EQ(Refusal(with("\"from\": 0.5", "\"from\": 1")),
            "generic.json: /truths/0/from: 1 s is not before the end of the "
            "run (the run ends at 1 s)");
  EXPECT_EQ(Refusal(with("\"from\": 0.5", "\"from\": 0.5, \"until\": 0.5")),
            "generic.json: /truths/0/from: 0.5 s is not before \"until\" (0.5 "
            "s): the window is empty");
  EXPECT_EQ(Refusal(with("\"absolute\": 0.001", "\"absolute\": -0.001")),
            "generic.json: /truths/0/tolerance/absolute: must be >= 0");
  EXPECT_EQ(Refusal(with("\"absolute\": 0.001", "\"relative\": 0.1")),
            "generic.json: /truths/0/tolerance/absolute: is required (metres): "
            "the truth is 0, so a relative "
            "tolerance alone allows nothing");
  EXPECT_EQ(Refusal(with("\"reason\": \"tilt\"", "\"reason\": \" \"")),
            "generic.json: /truths/0/maxTilt/reason: is empty; say where the "
            "bound comes from");
  EXPECT_EQ(Refusal(with(", \"reason\": \"drift\"", "")),
            "generic.json: /truths/0/tolerance: missing required field \"reason\"");
}

const std::string kMoves =
    R"({"kind": "moves", "body": "b", "distance": 0.5, "within": 0.8,
        "tolerance": {"absolute": 0.01, "reason": "slop"}})";

TEST(MovesTruth, AFallingBodyPassesAndOneHeldUpFails) {
  const ScenarioRun run = Load(kMoves);
  const Truth& truth = run.scenario.truths.front();
  // b falls freely: 0.5 g t^2 = 3.1 m by 0.8 s.
  const auto falls = [&](std::size_t b, double t) {
    BodyReading reading = Still(run, b);
    if (b == 2) reading.centerOfMass.y() -= 0.5 * kG * t * t;
    return reading;
  };
  auto metrics = EvaluateTruth(run, truth, Track(run, falls, 7));
  ASSERT_EQ(metrics.size(), 1u);
  EXPECT_EQ(metrics[0].name, "moves.shortfall.b");
  EXPECT_TRUE(metrics[0].pass);
  EXPECT_EQ(metrics[0].measured, 0.0);
  // Held up (an engine that invents friction): short by the whole distance.
  metrics = EvaluateTruth(run, truth, Track(run, [&](std::size_t b, double) { return Still(run, b); }));
  EXPECT_FALSE(metrics[0].pass);
  EXPECT_EQ(metrics[0].measured, 0.5);
  // Falls, but only after `within`: too late.
  const auto late = [&](std::size_t b, double t) {
    BodyReading reading = Still(run, b);
    if (b == 2 && t > 0.85) reading.centerOfMass.y() -= 1.0;
    return reading;
  };
  EXPECT_FALSE(EvaluateTruth(run, truth, Track(run, late))[0].pass);
  // Moves 0.495 m: within the 1 cm tolerance of the distance.
  const auto nearly = [&](std::size_t b, double t) {
    BodyReading reading = Still(run, b);
    if (b == 2 && t > 0.5) reading.centerOfMass.x() += 0.495;
    return reading;
  };
  EXPECT_TRUE(EvaluateTruth(run, truth, Track(run, nearly))[0].pass);
  ExpectRoundTrip(run);
  EXPECT_EQ(Refusal(R"({"kind": "moves", "body": "c", "distance": 0.5, "within": 0.8,
                        "tolerance": {"absolute": 0.01, "reason": "slop"}})"),
            "generic.json: /truths/0/body: no body named \"c\"");
  EXPECT_EQ(Refusal(
                R"({"kind": "moves", "body": "ground", "distance": 0.5, "within": 0.8,
                        "tolerance": {"absolute": 0.01, "reason": "slop"}})"),
            "generic.json: /truths/0/body: moves needs a dynamic body (a static one "
            "never moves)");
  EXPECT_EQ(Refusal(R"({"kind": "moves", "body": "b", "distance": 0.5, "within": 1.5,
                        "tolerance": {"absolute": 0.01, "reason": "slop"}})"),
            "generic.json: /truths/0/within: 1.5 s is after the end of the run (the "
            "run ends at 1 s)");
  EXPECT_EQ(Refusal(R"({"kind": "moves", "body": "b", "distance": 0, "within": 0.5,
                        "tolerance": {"absolute": 0.01, "reason": "slop"}})"),
            "generic.json: /truths/0/distance: must be > 0");
}

TEST(StateAtTruth, TheStatedStateAtTheTimePassesAndAnotherFails) {
  // b at constant velocity (1, 0, -2) m/s, so a strided trajectory
  // interpolates it exactly: at 0.55 s (between samples) it is at
  // (1.55, 1, -1.1).
  const ScenarioRun run = Load(
      R"({"kind": "state_at", "body": "b", "quantity": "position", "time": 0.55,
      "value": [1.55, 1, -1.1], "tolerance": {"absolute": 1e-9, "reason": "exact"}})");
  const auto cruises = [&](std::size_t b, double t) {
    BodyReading reading = Still(run, b);
    if (b == 2) {
      reading.linearVelocity = Vec3(1, 0, -2);
      reading.centerOfMass += reading.linearVelocity * t;
    }
    return reading;
  };
  auto metrics = EvaluateTruth(run, run.scenario.truths.front(), Track(run, cruises, 4));
  ASSERT_EQ(metrics.size(), 1u);
  EXPECT_EQ(metrics[0].name, "state_at.position.b");
  EXPECT_TRUE(metrics[0].pass) << metrics[0].measured;
  // 1 cm/s slower along x: 5.5 mm behind at 0.55 s.
  const auto slower = [&](std::size_t b, double t) {
    BodyReading reading = cruises(b, t);
    if (b == 2) reading.centerOfMass.x() -= 0.01 * t;
    return reading;
  };
  metrics = EvaluateTruth(run, run.scenario.truths.front(), Track(run, slower, 4));
  EXPECT_FALSE(metrics[0].pass);
  EXPECT_NEAR(metrics[0].measured, 0.0055, 1e-12);
  ExpectRoundTrip(run);

  const ScenarioRun velocity = Load(
      R"({"kind": "state_at", "body": "b", "quantity": "velocity", "time": 1,
      "value": [1, 0, -2], "tolerance": {"absolute": 1e-9, "reason": "exact"}})");
  EXPECT_TRUE(EvaluateTruth(velocity, velocity.scenario.truths.front(), Track(velocity, cruises))[0].pass);
  EXPECT_FALSE(EvaluateTruth(velocity, velocity.scenario.truths.front(),
                             Track(velocity, [&](std::size_t b, double) { return Still(velocity, b); }))[0]
                   .pass);
}

TEST(StateAtTruth, AnOrientationIsJudgedByTheAngleBetween) {
  // a turns at 2 rad/s about y: at 0.5 s it has turned 1 rad.
  const double half = 0.5;
  const ScenarioRun run = Load(
      R"({"kind": "state_at", "body": "a", "quantity": "orientation", "time": 0.5,
      "value": [)" +
      std::to_string(std::cos(half)) + ", 0, " + std::to_string(std::sin(half)) +
      R"(, 0], "tolerance": {"absolute": 1e-5, "reason": "written to 6 digits"}})");
  const auto turns = [&](std::size_t b, double t) {
    BodyReading reading = Still(run, b);
    if (b == 1) reading.orientation = Quat(Eigen::AngleAxisd(2.0 * t, Vec3::UnitY()));
    return reading;
  };
  auto metrics = EvaluateTruth(run, run.scenario.truths.front(), Track(run, turns, 3));
  ASSERT_EQ(metrics.size(), 1u);
  EXPECT_EQ(metrics[0].name, "state_at.orientation.a");
  EXPECT_EQ(metrics[0].unit, "rad");
  EXPECT_TRUE(metrics[0].pass) << metrics[0].measured;
  // Turning at 2.2 rad/s: 0.1 rad ahead at 0.5 s.
  const auto faster = [&](std::size_t b, double t) {
    BodyReading reading = Still(run, b);
    if (b == 1) reading.orientation = Quat(Eigen::AngleAxisd(2.2 * t, Vec3::UnitY()));
    return reading;
  };
  metrics = EvaluateTruth(run, run.scenario.truths.front(), Track(run, faster, 3));
  EXPECT_FALSE(metrics[0].pass);
  EXPECT_NEAR(metrics[0].measured, 0.1, 1e-5);
  ExpectRoundTrip(run);
}

TEST(StateAtTruth, LoaderRefusesWhatCannotBeJudged) {
  EXPECT_EQ(Refusal(
                R"({"kind": "state_at", "body": "a", "quantity": "position", "time": 1.5, "value": [0, 1, 0],
      "tolerance": {"absolute": 1e-3, "reason": "r"}})"),
            "generic.json: /truths/0/time: 1.5 s is after the end of the run (the "
            "run ends at 1 s)");
  EXPECT_EQ(
      Refusal(
          R"({"kind": "state_at", "body": "a", "quantity": "orientation", "time": 0.5, "value": [0, 1, 0],
      "tolerance": {"absolute": 1e-3, "reason": "r"}})"),
      "generic.json: /truths/0/value: an orientation is a quaternion [w, x, y, "
      "z]");
  EXPECT_EQ(Refusal(
                R"({"kind": "state_at", "body": "a", "quantity": "orientation", "time": 0.5,
      "value": [1, 0, 0.1, 0], "tolerance": {"absolute": 1e-3, "reason": "r"}})"),
            "generic.json: /truths/0/value: quaternion is not unit length (norm "
            "1.00499)");
  EXPECT_EQ(Refusal(
                R"({"kind": "state_at", "body": "a", "quantity": "velocity", "time": 0.5,
      "value": [1, 0, 0, 0], "tolerance": {"absolute": 1e-3, "reason": "r"}})"),
            "generic.json: /truths/0/value: a position or velocity is [x, y, z]");
  EXPECT_EQ(Refusal(
                R"({"kind": "state_at", "body": "ground", "quantity": "position", "time": 0.5,
      "value": [0, 1, 0], "tolerance": {"absolute": 1e-3, "reason": "r"}})"),
            "generic.json: /truths/0/body: state_at needs a dynamic body (a static "
            "one keeps its state)");
  EXPECT_EQ(Refusal(
                R"({"kind": "state_at", "body": "a", "quantity": "spin", "time": 0.5,
      "value": [0, 1, 0], "tolerance": {"absolute": 1e-3, "reason": "r"}})"),
            "generic.json: /truths/0/quantity: must be one of "
            "[\"position\",\"velocity\",\"orientation\"]");
}

TEST(EnergyNotIncreasingTruth, FreeFallKeepsItAndAnEnergeticBounceFails) {
  const ScenarioRun run = Load(R"({"kind": "energy_not_increasing", "bodies": ["a"],
      "tolerance": {"absolute": 1e-9, "reason": "exact states"}})");
  const Truth& truth = run.scenario.truths.front();
  // a falls freely: kinetic energy gained is potential lost, exactly.
  const auto falls = [&](std::size_t b, double t) {
    BodyReading reading = Still(run, b);
    if (b == 1) {
      reading.centerOfMass.y() -= 0.5 * kG * t * t;
      reading.linearVelocity = Vec3(0, -kG * t, 0);
    }
    return reading;
  };
  auto metrics = EvaluateTruth(run, truth, Track(run, falls));
  ASSERT_EQ(metrics.size(), 1u);
  EXPECT_EQ(metrics[0].name, "energy_not_increasing.rise");
  EXPECT_TRUE(metrics[0].pass) << metrics[0].measured;
  // From 0.5 s on it moves 10 % faster than it falls (the speed a solver
  // made): the extra kinetic energy 2 kg x (1.21 - 1) (g t)^2 / 2 is
  // largest at the end, 0.21 g^2 J at t = 1 s.
  const auto bounces = [&](std::size_t b, double t) {
    BodyReading reading = falls(b, t);
    if (b == 1 && t >= 0.5) reading.linearVelocity.y() *= -1.1;
    return reading;
  };
  metrics = EvaluateTruth(run, truth, Track(run, bounces, 5));
  EXPECT_FALSE(metrics[0].pass);
  EXPECT_NEAR(metrics[0].measured, 0.21 * kG * kG, 1e-9);
  ExpectRoundTrip(run);
  EXPECT_EQ(Refusal(R"({"kind": "energy_not_increasing", "bodies": ["ground"],
      "tolerance": {"absolute": 1e-3, "reason": "r"}})"),
            "generic.json: /truths/0/bodies/0: body \"ground\" is static");
}

TEST(MomentumConservedTruth, AnElasticCollisionKeepsItAndAOneSidedImpulseFails) {
  const ScenarioRun run = Load(R"({"kind": "momentum_conserved",
      "tolerance": {"absolute": 1e-12, "reason": "exact states"}})",
                               true);
  const Truth& truth = run.scenario.truths.front();
  // a (2 kg, 1 m/s) hits b (3 kg, at rest) at 0.5 s, elastically: a leaves
  // at (2 - 3) / 5 = -0.2 m/s, b at 2 x 2 / 5 = 0.8 m/s; 2 kg m/s before and
  // after.
  const auto collides = [&](std::size_t b, double t) {
    BodyReading reading = Still(run, b);
    if (b == 0) reading.linearVelocity = Vec3(t < 0.5 ? 1.0 : -0.2, 0, 0);
    if (b == 1) reading.linearVelocity = Vec3(t < 0.5 ? 0.0 : 0.8, 0, 0);
    return reading;
  };
  auto metrics = EvaluateTruth(run, truth, Track(run, collides));
  ASSERT_EQ(metrics.size(), 1u);
  EXPECT_EQ(metrics[0].name, "momentum_conserved.drift");
  EXPECT_TRUE(metrics[0].pass) << metrics[0].measured;
  // The impulse applied to b alone: 0.3 kg m/s from nowhere.
  const auto oneSided = [&](std::size_t b, double t) {
    BodyReading reading = collides(b, t);
    if (b == 1 && t >= 0.5) reading.linearVelocity.x() = 0.9;
    return reading;
  };
  metrics = EvaluateTruth(run, truth, Track(run, oneSided));
  EXPECT_FALSE(metrics[0].pass);
  EXPECT_NEAR(metrics[0].measured, 0.3, 1e-12);
  ExpectRoundTrip(run);
  EXPECT_EQ(Refusal(R"({"kind": "momentum_conserved", "tolerance": {"absolute": 1e-3, "reason": "r"}})"),
            "generic.json: /truths/0/kind: momentum_conserved needs a world without "
            "gravity (gravity adds "
            "momentum)");
}

TEST(MaxPenetrationTruth, ShallowContactsPassAndASinkingBodyFails) {
  const ScenarioRun run = Load(R"({"kind": "max_penetration", "from": 0.2,
      "tolerance": {"absolute": 0.005, "reason": "slop"}})");
  const Truth& truth = run.scenario.truths.front();
  const auto still = [&](std::size_t b, double) { return Still(run, b); };
  // 2 mm deep, after a 5 cm overlap at the start that `from` leaves out.
  const auto resting = [](double t) { return t < 0.1 ? 0.05 : 0.002; };
  auto metrics = EvaluateTruth(run, truth, Track(run, still, 1, resting));
  ASSERT_EQ(metrics.size(), 1u);
  EXPECT_EQ(metrics[0].name, "max_penetration.depth");
  EXPECT_TRUE(metrics[0].pass);
  EXPECT_EQ(metrics[0].measured, 0.002);
  // Sinking 1 cm at 0.7 s: past the 5 mm bound.
  const auto sinks = [](double t) { return t >= 0.7 && t < 0.75 ? 0.01 : 0.002; };
  metrics = EvaluateTruth(run, truth, Track(run, still, 1, sinks));
  EXPECT_FALSE(metrics[0].pass);
  EXPECT_EQ(metrics[0].measured, 0.01);
  ExpectRoundTrip(run);
  EXPECT_EQ(
      Refusal(R"({"kind": "max_penetration", "from": 1, "tolerance": {"absolute": 1e-3, "reason": "r"}})"),
      "generic.json: /truths/0/from: 1 s is not before the end of the run (the "
      "run ends at 1 s)");
  EXPECT_EQ(Refusal(R"({"kind": "max_penetration", "tolerance": {"relative": 1e-3, "reason": "r"}})"),
            "generic.json: /truths/0/tolerance/absolute: is required (metres): the "
            "truth is 0, so a relative "
            "tolerance alone allows nothing");
}

}  // namespace generic_truths_test
}  // namespace talus::harness
