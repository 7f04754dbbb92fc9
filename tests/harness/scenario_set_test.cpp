// The shipped scenario set: every file loads, sweeps expand into the runs
// the files promise, the new truth kinds map to what the closed forms need,
// and bad values of every new field are refused with the field's pointer.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <utility>

#include "talus/harness/analytic/hull_rest_analysis.h"
#include "talus/harness/analytic/torque_free_motion.h"
#include "talus/harness/analytic/truths.h"
#include "talus/harness/scenario/scenario_loader.h"

namespace talus::harness {
namespace scenario_set_test {

using nlohmann::json;

const std::string kScenarioDir = TALUS_SCENARIO_DIR;

std::vector<harness::Run> Load(const std::string& file) {
  auto runs = LoadScenarioFile(kScenarioDir + "/" + file);
  EXPECT_TRUE(runs) << (runs ? "" : runs.GetError().message);
  return runs ? runs.Value() : std::vector<harness::Run>{};
}

TEST(ScenarioSet, EveryScenarioFileLoadsIntoItsRuns) {
  const std::map<std::string, size_t> expected = {
      {"stacking/box_rest.json", 1},
      {"stacking/box_column_2.json", 1},
      {"stacking/box_column_5.json", 1},
      {"stacking/box_column_10.json", 1},
      {"stacking/box_pyramid_4.json", 1},
      {"stacking/hull_rest.json", 1},
      {"sliding/box_slide.json", 6},
      {"sliding/box_slide_directions.json", 12},
      {"sliding/box_incline.json", 5},
      {"sliding/tall_box_tipping.json", 5},
      {"tumbling/box_free_fall.json", 1},
      {"tumbling/box_torque_free.json", 1},
      {"tumbling/box_intermediate_axis.json", 1},
      {"tumbling/box_toss.json", 1},
      {"bouncing/sphere_bounce.json", 1},
      {"bouncing/sphere_bounce_series.json", 3},
      {"mass_ratio/slab_on_two_boxes.json", 4},
      {"mass_ratio/heavy_box_on_pyramid.json", 3},
      {"mass_ratio/load_removed.json", 1},
      {"mass_ratio/graded_column.json", 1},
      {"mass_ratio/ball_on_box.json", 1},
      {"structures/arch_stands.json", 1},
      {"structures/arch_falls.json", 1},
      {"bouncing/elastic_grid_7x7.json", 1},
      {"rolling/sphere_incline.json", 1},
      {"rolling/simbenchmark_rolling.json", 1},
      {"rolling/simbenchmark_rolling_diagonal.json", 1},
      {"stacking/far_pyramid_4.json", 1},
      {"stacking/far_column_5.json", 1},
      {"sliding/far_box_slide.json", 1},
      {"structures/card_house.json", 1},
      {"structures/dominoes.json", 1},
      {"structures/overlap_recovery.json", 1},
  };
  for (const auto& [file, count] : expected) {
    const auto runs = Load(file);
    EXPECT_EQ(runs.size(), count) << file;
    for (const harness::Run& run : runs) {
      EXPECT_FALSE(run.scenario.description.empty()) << file << " needs a description";
      EXPECT_FALSE(run.scenario.truths.empty()) << file << " has no truth";
    }
  }
}

TEST(ScenarioSet, StructureScenesJudgeEveryBodyTheyBuild) {
  // The card house holds every card at rest; the dominoes topple in the
  // order they stand along x, struck at the first; the overlap pile's push-out
  // bound covers every box.
  const auto house = Load("structures/card_house.json");
  ASSERT_EQ(house.size(), 1u);
  EXPECT_EQ(std::get<AtRestTruth>(house[0].scenario.truths[0].kind).bodies.size(), 40u);
  const auto row = Load("structures/dominoes.json");
  ASSERT_EQ(row.size(), 1u);
  const Scenario& dominoes = row[0].scenario;
  const auto& topples = std::get<TopplesTruth>(dominoes.truths[0].kind);
  ASSERT_EQ(topples.bodies.size(), 15u);
  for (std::size_t i = 1; i < topples.bodies.size(); ++i) {
    EXPECT_GT(dominoes.bodies[topples.bodies[i]].position.x(),
              dominoes.bodies[topples.bodies[i - 1]].position.x());
  }
  ASSERT_EQ(dominoes.impulses.size(), 1u);
  EXPECT_EQ(dominoes.impulses[0].body, topples.bodies[0]);
  const auto pile = Load("structures/overlap_recovery.json");
  ASSERT_EQ(pile.size(), 1u);
  EXPECT_EQ(std::get<MaxSpeedTruth>(pile[0].scenario.truths[0].kind).bodies.size(), 10u);
}

TEST(ScenarioSet, ColumnsListOneBoxPerLayerRestingOnEachOther) {
  for (const int n : {2, 5, 10}) {
    const auto runs = Load("stacking/box_column_" + std::to_string(n) + ".json");
    ASSERT_EQ(runs.size(), 1u);
    const Scenario& s = runs[0].scenario;
    ASSERT_EQ(s.truths[0].body, -1);
    const auto& truth = std::get<StackRestTruth>(s.truths[0].kind);
    ASSERT_EQ(truth.layers.size(), static_cast<size_t>(n));
    for (int layer = 0; layer < n; ++layer) {
      ASSERT_EQ(truth.layers[layer].size(), 1u);
      // Placed exactly where the truth says they rest: no drop, no overlap.
      EXPECT_NEAR(s.bodies[truth.layers[layer][0]].position.y(),
                  StackRestHeight(truth.floor, truth.layerHeight, layer), 1e-12);
    }
    EXPECT_EQ(runs[0].steps, 600);  // 10 s at 60 Hz
  }
}

TEST(ScenarioSet, PyramidLayersShrinkByOne) {
  const auto runs = Load("stacking/box_pyramid_4.json");
  ASSERT_EQ(runs.size(), 1u);
  const auto& truth = std::get<StackRestTruth>(runs[0].scenario.truths[0].kind);
  ASSERT_EQ(truth.layers.size(), 4u);
  for (size_t layer = 0; layer < 4; ++layer) EXPECT_EQ(truth.layers[layer].size(), 4 - layer);
}

TEST(ScenarioSet, HullRestHeightIsTheCentroidDistanceToTheBottomFace) {
  const auto runs = Load("stacking/hull_rest.json");
  ASSERT_EQ(runs.size(), 1u);
  const Scenario& s = runs[0].scenario;
  const auto& truth = std::get<HullRestTruth>(s.truths[0].kind);
  const auto& points = std::get<HullShape>(s.bodies[1].shape).points;
  // Independent: the bottom face is the plane y = 0 of the body frame, so
  // the height is the centroid's y, here from the divergence theorem over
  // the hull's faces (the analysis's centroid) checked against the lowest point.
  const auto analysis = AnalyseHullRest(points);
  ASSERT_TRUE(analysis);
  double lowest = 1e9;
  for (const Vec3& p : points) lowest = std::min(lowest, p.y());
  EXPECT_EQ(lowest, 0.0);
  EXPECT_NEAR(truth.height, analysis.Value().centroid.y(), 1e-12);
  EXPECT_NEAR(truth.faceNormal.y(), -1.0, 1e-12);
  // The centroid is off the body origin in every direction: a backend that
  // puts the centre of mass at the origin is caught.
  EXPECT_GT(std::abs(analysis.Value().centroid.x()), 0.1);
  EXPECT_GT(std::abs(analysis.Value().centroid.z()), 0.1);
  const int bottom = analysis.Value().NearestFace(Vec3(0, -1, 0));
  EXPECT_GT(analysis.Value().faces[bottom].margin, 0.3) << "the resting face must be unambiguous";
}

TEST(ScenarioSet, TwelveDirectionsLaunchAtTheSameSpeedAlongTheTruthDirection) {
  const auto runs = Load("sliding/box_slide_directions.json");
  ASSERT_EQ(runs.size(), 12u);
  for (int k = 0; k < 12; ++k) {
    const harness::Run& run = runs[k];
    EXPECT_EQ(run.id, "box_slide_directions[direction=" + std::to_string(30 * k) + "deg]");
    const auto& truth = std::get<SlidingStopTruth>(run.scenario.truths[0].kind);
    const double angle = 30.0 * k * std::numbers::pi / 180.0;
    EXPECT_LT((truth.direction - Vec3(std::cos(angle), 0, std::sin(angle))).norm(), 1e-12);
    EXPECT_LT((run.scenario.bodies[1].linearVelocity - truth.v0 * truth.direction).norm(), 1e-12);
  }
}

TEST(ScenarioSet, InclineSweepPlacesTheBoxOnTheTurnedSlope) {
  for (const char* file : {"sliding/box_incline.json", "sliding/tall_box_tipping.json"}) {
    for (const harness::Run& run : Load(file)) {
      const BodySpec& slope = run.scenario.bodies[0];
      const BodySpec& box = run.scenario.bodies[1];
      const double angle = std::visit(
          [](const auto& t) -> double {
            if constexpr (requires { t.angle; }) return t.angle;
            return -1.0;
          },
          run.scenario.truths[0].kind);
      // Slope and box turned by the truth's angle, the box's bottom face on
      // the slope's top face (the slope is 1 m thick, centred at the origin).
      EXPECT_NEAR(slope.orientation.angularDistance(box.orientation), 0.0, 1e-12) << run.id;
      EXPECT_NEAR(Eigen::AngleAxisd(slope.orientation).angle(), angle, 1e-12) << run.id;
      const Vec3 normal = slope.orientation * Vec3::UnitY();
      const double halfHeight = std::get<BoxShape>(box.shape).halfExtents.y();
      EXPECT_NEAR(box.position.dot(normal), 0.5 + halfHeight, 1e-12) << run.id;
      EXPECT_NEAR((box.position - box.position.dot(normal) * normal).norm(), 0.0, 1e-12) << run.id;
    }
  }
}

TEST(ScenarioSet, SweepsStraddleTheSlidingAndTippingThresholds) {
  int slides = 0, holds = 0;
  for (const harness::Run& run : Load("sliding/box_incline.json")) {
    const auto& t = std::get<InclineSlideTruth>(run.scenario.truths[0].kind);
    (InclineAcceleration(t.angle, t.mu, t.g) > 0.0 ? slides : holds)++;
  }
  EXPECT_EQ(slides, 2);
  EXPECT_EQ(holds, 3);
  std::vector<InclineOutcome> outcomes;
  std::vector<double> offsets;  // degrees from the tipping threshold
  for (const harness::Run& run : Load("sliding/tall_box_tipping.json")) {
    const auto& t = std::get<InclineTipTruth>(run.scenario.truths[0].kind);
    outcomes.push_back(InclineBoxOutcome(t.angle, t.mu, t.width, t.height));
    offsets.push_back((t.angle - std::atan(t.width / t.height)) * 180.0 / std::numbers::pi);
    // The friction the truth assumes is the bodies' (sqrt combine of equals).
    EXPECT_EQ(run.scenario.bodies[0].friction, t.mu) << run.id;
    EXPECT_EQ(run.scenario.bodies[1].friction, t.mu) << run.id;
  }
  EXPECT_EQ(outcomes,
            (std::vector<InclineOutcome>{InclineOutcome::Stays, InclineOutcome::Stays, InclineOutcome::Tips,
                                         InclineOutcome::Tips, InclineOutcome::Slides}));
  // The two runs nearest the threshold bracket it 0.3 degree either side.
  EXPECT_NEAR(offsets[1], -0.3, 1e-9);
  EXPECT_NEAR(offsets[2], 0.3, 1e-9);
}

TEST(ScenarioSet, SpinTruthsDescribeTheirBox) {
  const auto runs = Load("tumbling/box_intermediate_axis.json");
  ASSERT_EQ(runs.size(), 1u);
  const Scenario& s = runs[0].scenario;
  EXPECT_EQ(s.world.gravity, Vec3::Zero());
  const auto& flip = std::get<FlipPeriodTruth>(s.truths[1].kind);
  EXPECT_EQ(IntermediateAxis(flip.inertia), 1);
  auto interval = IntermediateAxisFlipInterval(flip.inertia, flip.omega);
  ASSERT_TRUE(interval);
  // The run must hold at least three flips for two measured intervals.
  EXPECT_GT(runs[0].steps * runs[0].timeStep, 3.0 * interval.Value());
  const TorqueFreeTruth spin =
      std::get<TorqueFreeTruth>(Load("tumbling/box_torque_free.json")[0].scenario.truths[0].kind);
  EXPECT_EQ(spin.omega, Vec3(0.5, 0.5, 3.0));
}

TEST(ScenarioSet, BounceSeriesSweepsRestitutionIntoBodyAndTruth) {
  const auto runs = Load("bouncing/sphere_bounce_series.json");
  ASSERT_EQ(runs.size(), 3u);
  const double values[] = {0.5, 0.7, 0.9};
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(runs[i].scenario.bodies[1].restitution, values[i]);
    const auto& truth = std::get<BounceHeightsTruth>(runs[i].scenario.truths[0].kind);
    EXPECT_EQ(truth.e, values[i]);
    EXPECT_EQ(truth.count, 4);
  }
}

// The rolling sphere's truths are the closed form of rolling without slip,
// computed here from the file's slope, sphere and gravity: a = 5/7 g sin,
// s = a t^2 / 2 down the slope from a start touching the slope, with
// friction enough to roll (mu > 2/7 tan).
TEST(ScenarioSet, RollingSphereTruthsAreRollingWithoutSlip) {
  const auto runs = Load("rolling/sphere_incline.json");
  ASSERT_EQ(runs.size(), 1u);
  const Scenario& s = runs[0].scenario;
  const BodySpec& slope = s.bodies[0];
  const BodySpec& ball = s.bodies[1];
  const double angle = Eigen::AngleAxisd(slope.orientation).angle();
  const Vec3 normal = slope.orientation * Vec3::UnitY();
  const Vec3 down = -(slope.orientation * Vec3::UnitX());
  const double radius = std::get<SphereShape>(ball.shape).radius;
  EXPECT_NEAR(ball.position.dot(normal), 0.5 + radius, 1e-12);
  const double g = s.world.gravity.norm();
  const double mu = Combine(s.world.frictionCombine, slope.friction, ball.friction);
  EXPECT_GT(mu, 3.0 * 2.0 / 7.0 * std::tan(angle)) << "the file states a margin of 3";
  const double a = 5.0 / 7.0 * g * std::sin(angle);
  const auto& position = std::get<StateAtTruth>(s.truths[0].kind);
  const auto& velocity = std::get<StateAtTruth>(s.truths[1].kind);
  ASSERT_EQ(position.quantity, StateQuantity::Position);
  ASSERT_EQ(velocity.quantity, StateQuantity::Velocity);
  const double t = position.time;
  EXPECT_LT((position.value - (ball.position + 0.5 * a * t * t * down)).norm(), 1e-12);
  EXPECT_LT((velocity.value - a * velocity.time * down).norm(), 1e-12);
}

// SimBenchmark's rolling: the file's per-body coefficients under its
// combine rule give the derivation's pairs (0.4 box-ground, 0.8 ball-box),
// and every truth is A t (box) or 2/7 A t (ball) along the push, with A
// from the derivation in docs/scenarios.md recomputed from the bodies.
TEST(ScenarioSet, SimBenchmarkRollingTruthsFollowTheDerivation) {
  const double root = 1.0 / std::sqrt(2.0);
  for (const auto& [file, push] :
       {std::pair{"rolling/simbenchmark_rolling.json", Vec3(1, 0, 0)},
        std::pair{"rolling/simbenchmark_rolling_diagonal.json", Vec3(root, 0, root)}}) {
    const auto runs = Load(file);
    ASSERT_EQ(runs.size(), 1u) << file;
    const Scenario& s = runs[0].scenario;
    const BodySpec& ground = s.bodies[0];
    const BodySpec& box = s.bodies[1];
    ASSERT_EQ(box.name, "box");
    ASSERT_EQ(s.bodies.size(), 27u) << file;
    const double groundMu = Combine(s.world.frictionCombine, ground.friction, box.friction);
    EXPECT_NEAR(groundMu, 0.4, 1e-12) << file;
    double ballMass = 0.0;
    for (std::size_t b = 2; b < s.bodies.size(); ++b) {
      EXPECT_NEAR(Combine(s.world.frictionCombine, box.friction, s.bodies[b].friction), 0.8, 1e-12) << file;
      ballMass += s.bodies[b].mass;
      // Resting on the box's top face, never touching each other.
      EXPECT_NEAR(s.bodies[b].position.y(), 1.0 + std::get<SphereShape>(s.bodies[b].shape).radius, 1e-12);
    }
    ASSERT_EQ(s.loads.size(), 1u);
    EXPECT_LT((s.loads[0].force - 150.0 * push).norm(), 1e-9) << file;
    const double g = s.world.gravity.norm();
    const double A = (150.0 - groundMu * (box.mass + ballMass) * g) / (box.mass + 2.0 / 7.0 * ballMass);
    EXPECT_NEAR(A, 0.7385, 5e-5);  // the benchmark's figure
    for (const Truth& truth : s.truths) {
      const auto& at = std::get<StateAtTruth>(truth.kind);
      ASSERT_EQ(at.quantity, StateQuantity::Velocity);
      const double speed = (truth.body == 1 ? A : 2.0 / 7.0 * A) * at.time;
      EXPECT_LT((at.value - speed * push).norm(), 1e-12) << file << " " << s.bodies[truth.body].name;
    }
  }
}

// The elastic grid: 49 balls that bounce with e = 1 and never touch each
// other, so the energy is the only thing judged.
TEST(ScenarioSet, ElasticGridBallsAreElasticFrictionlessAndApart) {
  const auto runs = Load("bouncing/elastic_grid_7x7.json");
  ASSERT_EQ(runs.size(), 1u);
  const Scenario& s = runs[0].scenario;
  ASSERT_EQ(s.bodies.size(), 50u);
  for (std::size_t b = 1; b < s.bodies.size(); ++b) {
    EXPECT_EQ(Combine(s.world.restitutionCombine, s.bodies[0].restitution, s.bodies[b].restitution), 1.0);
    EXPECT_EQ(Combine(s.world.frictionCombine, s.bodies[0].friction, s.bodies[b].friction), 0.0);
    for (std::size_t c = b + 1; c < s.bodies.size(); ++c) {
      EXPECT_GT((s.bodies[b].position - s.bodies[c].position).norm(), 1.5);
    }
  }
  // No rise anywhere, and the centre ball back at H at each apex: the
  // energy stays n^2 m g H either way.
  ASSERT_EQ(s.truths.size(), 2u);
  EXPECT_TRUE(std::holds_alternative<EnergyNotIncreasingTruth>(s.truths[0].kind));
  for (std::size_t t = 1; t < s.truths.size(); ++t) {
    const auto& apexes = std::get<BounceHeightsTruth>(s.truths[t].kind);
    const BodySpec& ball = s.bodies[s.truths[t].body];
    EXPECT_EQ(apexes.e, 1.0);
    EXPECT_NEAR(ball.position.y() - std::get<SphereShape>(ball.shape).radius, apexes.h, 1e-12);
  }
}

// Far from the origin: each file is its near-origin counterpart moved by
// (1e5, 0, -8e4) m, with the same truths and tolerances.
TEST(ScenarioSet, FarScenesAreTheNearOnesMoved) {
  const Vec3 offset(1e5, 0, -8e4);
  for (const auto& [far, near] : {std::pair{"stacking/far_pyramid_4.json", "stacking/box_pyramid_4.json"},
                                  std::pair{"stacking/far_column_5.json", "stacking/box_column_5.json"},
                                  std::pair{"sliding/far_box_slide.json", "sliding/box_slide.json"}}) {
    const auto farRuns = Load(far);
    const auto nearRuns = Load(near);
    ASSERT_EQ(farRuns.size(), 1u) << far;
    ASSERT_FALSE(nearRuns.empty()) << near;
    // box_slide's run with the far file's friction and speed.
    const harness::Run* match = nullptr;
    for (const harness::Run& run : nearRuns) {
      if (run.scenario.bodies[1].friction == farRuns[0].scenario.bodies[1].friction &&
          run.scenario.bodies[1].linearVelocity == farRuns[0].scenario.bodies[1].linearVelocity) {
        match = &run;
      }
    }
    ASSERT_NE(match, nullptr) << far;
    const Scenario& f = farRuns[0].scenario;
    const Scenario& n = match->scenario;
    ASSERT_EQ(f.bodies.size(), n.bodies.size()) << far;
    for (std::size_t b = 0; b < f.bodies.size(); ++b) {
      EXPECT_EQ(f.bodies[b].position, n.bodies[b].position + offset) << far << " " << f.bodies[b].name;
    }
    EXPECT_EQ(farRuns[0].steps, match->steps) << far;
    EXPECT_EQ(farRuns[0].timeStep, match->timeStep) << far;
    ASSERT_EQ(f.truths.size(), n.truths.size()) << far;
    for (std::size_t t = 0; t < f.truths.size(); ++t) {
      EXPECT_TRUE(f.truths[t].kind == n.truths[t].kind) << far;
      EXPECT_EQ(f.truths[t].tolerance.absolute, n.truths[t].tolerance.absolute) << far;
      EXPECT_EQ(f.truths[t].tolerance.relative, n.truths[t].tolerance.relative) << far;
    }
  }
}

// The two arch files are one structure at two frictions: the threshold in
// their descriptions (scripts/arch_friction_threshold.py, checked against
// docs by ctest docs.arch_friction_threshold) holds for both only if every
// block and its place are the same, and one friction on every body makes
// the combined coefficient that friction whatever the combine rule.
TEST(ScenarioSet, ArchFilesAreOneStructureAtTwoFrictions) {
  const auto stands = Load("structures/arch_stands.json");
  const auto falls = Load("structures/arch_falls.json");
  ASSERT_EQ(stands.size(), 1u);
  ASSERT_EQ(falls.size(), 1u);
  const auto& a = stands[0].scenario.bodies;
  const auto& b = falls[0].scenario.bodies;
  ASSERT_EQ(a.size(), 22u);  // ground, 17 blocks, 4 load boxes
  ASSERT_EQ(b.size(), a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].name, b[i].name);
    EXPECT_EQ(a[i].shape, b[i].shape) << a[i].name;
    EXPECT_EQ(a[i].position, b[i].position) << a[i].name;
    EXPECT_EQ(a[i].motion, b[i].motion) << a[i].name;
    EXPECT_EQ(a[i].density, b[i].density) << a[i].name;
    EXPECT_EQ(a[i].friction, 1.5) << a[i].name;
    EXPECT_EQ(b[i].friction, 0.37) << a[i].name;
  }
}

// --- Bad values of new fields, each refused with the field's pointer.

json SlideDoc() {
  return json::parse(R"({"name": "t", "world": {"timeStep": 0.01, "duration": {"steps": 10}},
    "bodies": [{"name": "ground", "shape": {"kind": "box", "halfExtents": [5, 0.5, 5]}, "motion": "static", "position": [0, -0.5, 0]},
               {"name": "box", "shape": {"kind": "box", "halfExtents": [0.5, 0.25, 0.125]}, "motion": "dynamic", "position": [0, 0.25, 0],
                "angularVelocity": [0.01, 3, 0.01], "density": 1000},
               {"name": "hull", "shape": {"kind": "hull", "points": [[0, 0, 0], [3, 0, 0], [4, 1, 0], [0, 0, 1], [3, 0, 1], [4, 1, 1]]},
                "motion": "dynamic", "position": [0, 0, 3], "density": 1000}],
    "truths": [{"kind": "sliding_stop", "body": "box", "v0": 1, "mu": 0.5, "g": 9.81,
                "maxLateral": {"value": 0.01, "reason": "1% of the friction force across the path"},
                "tolerance": {"relative": 0.01, "reason": "a friction coefficient 1% off"}}]})");
}

std::string Refusal(const json& doc) {
  auto runs = ParseScenarioText(doc.dump(), "t.json");
  EXPECT_FALSE(runs) << doc.dump() << " was accepted";
  return runs ? std::string() : runs.GetError().message;
}

// Every truth needs a tolerance with its reason, and every secondary bound
// of its kind a value with its reason; the truths below are about other
// fields, so they get them when they have none.
json WithTolerance(json truth) {
  if (!truth.contains("tolerance")) truth["tolerance"] = {{"absolute", 0.01}, {"reason", "one slop"}};
  const std::string kind = truth["kind"].get<std::string>();
  const auto bound = [&](const char* name, double value) {
    if (!truth.contains(name)) truth[name] = {{"value", value}, {"reason", "one slop of it"}};
  };
  if (kind == "sliding_stop") bound("maxLateral", 0.01);
  if (kind == "rest_height") bound("maxJitter", 0.001);
  if (kind == "stack_rest") bound("maxDrift", 0.004);
  if (kind == "hull_rest") bound("maxFaceAngle", 0.05);
  if (kind == "incline_tip") {
    bound("tiltThreshold", 0.5);
    bound("maxStayTilt", 0.025);
  }
  return truth;
}

void ExpectRefused(const json& truth, const std::string& expected) {
  json doc = SlideDoc();
  doc["truths"][0] = WithTolerance(truth);
  const std::string message = Refusal(doc);
  EXPECT_NE(message.find(expected), std::string::npos) << message;
}

TEST(ScenarioSet, BadSlidingDirectionsAreRefused) {
  json truth = SlideDoc()["truths"][0];
  truth["direction"] = {0, 1, 0};
  ExpectRefused(truth, "t.json: /truths/0/direction: must be perpendicular to gravity");
  truth["direction"] = {0, 0, 0};
  ExpectRefused(truth, "/truths/0/direction: direction has zero length");
  truth["direction"] = {1, 0};
  ExpectRefused(truth, "/truths/0/direction: needs at least 3 items");
  truth["direction"] = {1, 0, 0};
  truth["maxLateral"]["value"] = -0.1;
  ExpectRefused(truth, "/truths/0/maxLateral/value: must be >= 0");
}

TEST(ScenarioSet, BadStackLayersAreRefused) {
  json truth = {{"kind", "stack_rest"}, {"layers", {{"box"}, {"crate"}}}, {"floor", 0}, {"layerHeight", 0.5}};
  ExpectRefused(truth, "/truths/0/layers/1/0: no body named \"crate\"");
  truth["layers"] = {{"box"}, {"box"}};
  ExpectRefused(truth, "/truths/0/layers/1/0: body \"box\" is listed twice");
  truth["layers"] = {{"ground"}};
  ExpectRefused(truth, "/truths/0/layers/0/0: body \"ground\" is static");
  truth["layers"] = {{"box"}};
  truth["layerHeight"] = 0;
  ExpectRefused(truth, "/truths/0/layerHeight: must be > 0");
  truth["layerHeight"] = 0.5;
  truth["layers"] = json::array();
  ExpectRefused(truth, "/truths/0/layers: needs at least 1 items");
}

TEST(ScenarioSet, HullRestNeedsAStableFaceOfAHullBody) {
  json truth = {{"kind", "hull_rest"},
                {"body", "box"},
                {"faceNormal", {0, -1, 0}},
                {"floor", 0},
                {"height", 1.0 / 3.0}};
  ExpectRefused(truth, "/truths/0/body: hull_rest needs a hull body");
  truth["body"] = "hull";
  truth["faceNormal"] = {1, -0.5, 0};
  ExpectRefused(truth, "/truths/0/faceNormal: names no face of the hull");
  truth["faceNormal"] = {1, -1, 0};  // the slanted face of the obtuse prism (hull_rest_test)
  ExpectRefused(truth, "/truths/0/faceNormal: names an unstable face");
  truth["faceNormal"] = {0, 0, 0};
  ExpectRefused(truth, "/truths/0/faceNormal: normal has zero length");
  truth["faceNormal"] = {0, -1, 0};
  truth["maxFaceAngle"] = {{"value", -1}, {"reason", "a neighbouring face is further"}};
  ExpectRefused(truth, "/truths/0/maxFaceAngle/value: must be >= 0");
  truth.erase("maxFaceAngle");
  json doc = SlideDoc();
  doc["truths"][0] = WithTolerance(truth);
  auto runs = ParseScenarioText(doc.dump(), "t.json");
  ASSERT_TRUE(runs) << runs.GetError().message;
  // The height is the file's (computed without the engine), not the loader's.
  EXPECT_EQ(std::get<HullRestTruth>(runs.Value()[0].scenario.truths[0].kind).height, 1.0 / 3.0);
  truth.erase("height");
  ExpectRefused(truth, "/truths/0: missing required field \"height\"");
}

TEST(ScenarioSet, BadInclineFieldsAreRefused) {
  json slide = {{"kind", "incline_slide"}, {"body", "box"}, {"angle", 1.6}, {"mu", 0.5}, {"g", 9.81}};
  ExpectRefused(slide, "/truths/0/angle: must be <= 1.5");
  slide["angle"] = 0.3;
  slide["mu"] = -0.5;
  ExpectRefused(slide, "/truths/0/mu: must be >= 0");
  json tip = {
      {"kind", "incline_tip"}, {"body", "box"}, {"angle", 0.3}, {"mu", 0.8}, {"width", 0}, {"height", 1}};
  ExpectRefused(tip, "/truths/0/width: must be > 0");
  tip["width"] = 0.2;
  tip["tiltThreshold"] = {{"value", 0}, {"reason", "fallen over"}};
  ExpectRefused(tip, "/truths/0/tiltThreshold/value: must be > 0");
  tip["tiltThreshold"]["value"] = 0.02;
  ExpectRefused(tip, "/truths/0/maxStayTilt/value: must be below tiltThreshold");
  // An angle within the tolerance of the tipping threshold atan(0.2) = 11.3
  // degrees is not decided by the physics.
  tip.erase("tiltThreshold");
  tip["angle"] = 0.2;
  tip["tolerance"] = {{"absolute", 0.0087}, {"reason", "half a degree"}};
  ExpectRefused(tip, "/truths/0/angle: lies 0.149");
  tip["angle"] = 0.3;
  json doc = SlideDoc();
  doc["truths"][0] = WithTolerance(tip);
  EXPECT_TRUE(ParseScenarioText(doc.dump(), "t.json"));
}

TEST(ScenarioSet, SpinTruthsMustMatchTheirBox) {
  // The box's moments are in the proportions 0.078125 : 0.265625 : 0.3125.
  json truth = {{"kind", "torque_free"}, {"body", "box"}, {"inertia", {1, 2, 3}}, {"omega", {0.01, 3, 0.01}}};
  ExpectRefused(truth, "/truths/0/inertia: is not in the proportions of the box's principal moments");
  truth["inertia"] = {0.078125, 0.265625, -0.3125};
  ExpectRefused(truth, "/truths/0/inertia/2: must be > 0");
  truth["inertia"] = {0.78125, 2.65625, 3.125};
  truth["omega"] = {0.01, 3, 0.02};
  ExpectRefused(truth, "/truths/0/omega: differs from the body's angularVelocity");
  truth["omega"] = {0.01, 3, 0.01};
  truth["body"] = "hull";
  ExpectRefused(truth, "/truths/0/body: a spin truth needs a dynamic box body");
  truth["body"] = "box";
  truth["kind"] = "flip_period";
  json doc = SlideDoc();
  doc["truths"][0] = WithTolerance(truth);
  EXPECT_TRUE(ParseScenarioText(doc.dump(), "t.json"));
  doc["bodies"][1]["angularVelocity"] = {3, 0.01, 0.01};
  doc["truths"][0]["omega"] = {3, 0.01, 0.01};
  const std::string message = Refusal(doc);
  EXPECT_NE(message.find("/truths/0/omega: omega is not within 25 degrees of the intermediate axis 1"),
            std::string::npos)
      << message;
}

TEST(ScenarioSet, GateDefaultsToOnAndMustBeABoolean) {
  json doc = SlideDoc();
  auto runs = ParseScenarioText(doc.dump(), "t.json");
  ASSERT_TRUE(runs);
  EXPECT_TRUE(runs.Value()[0].scenario.truths[0].gate);
  doc["truths"][0]["gate"] = false;
  // Out of the gate for every backend only with a written reason.
  std::string message = Refusal(doc);
  EXPECT_NE(message.find("/truths/0/gate: is false without a \"gateReason\""), std::string::npos) << message;
  doc["truths"][0]["gateReason"] = " ";
  EXPECT_NE(Refusal(doc).find("/truths/0/gate: is false without"), std::string::npos);
  doc["truths"][0]["gateReason"] = "every engine measured stops 3% short";
  runs = ParseScenarioText(doc.dump(), "t.json");
  ASSERT_TRUE(runs) << runs.GetError().message;
  EXPECT_FALSE(runs.Value()[0].scenario.truths[0].gate);
  EXPECT_EQ(runs.Value()[0].scenario.truths[0].gateReason, "every engine measured stops 3% short");
  doc["truths"][0]["gate"] = true;
  message = Refusal(doc);
  EXPECT_NE(message.find("/truths/0/gateReason: is given but the truth is gated"), std::string::npos)
      << message;
  doc["truths"][0]["gate"] = "no";
  message = Refusal(doc);
  EXPECT_NE(message.find("/truths/0/gate: must be of type boolean, not string"), std::string::npos)
      << message;
}

TEST(ScenarioSet, EverySecondaryBoundNeedsItsReason) {
  // Written straight into the document: WithTolerance would fill the bound in.
  json doc = SlideDoc();
  const auto refusal = [&doc](const json& truth) {
    doc["truths"][0] = truth;
    return Refusal(doc);
  };
  json truth = SlideDoc()["truths"][0];
  truth.erase("maxLateral");
  EXPECT_NE(refusal(truth).find("/truths/0: missing required field \"maxLateral\""), std::string::npos);
  truth["maxLateral"] = 0.01;  // a bare number, the old form
  EXPECT_NE(refusal(truth).find("/truths/0/maxLateral: must be of type object"), std::string::npos);
  truth["maxLateral"] = {{"value", 0.01}};
  EXPECT_NE(refusal(truth).find("/truths/0/maxLateral: missing required field \"reason\""),
            std::string::npos);
  truth["maxLateral"]["reason"] = "\t ";
  EXPECT_NE(refusal(truth).find("/truths/0/maxLateral/reason: is empty; say where the bound comes from"),
            std::string::npos);
  truth["maxLateral"]["reason"] = "1% of the friction force across the path";
  doc["truths"][0] = truth;
  auto runs = ParseScenarioText(doc.dump(), "t.json");
  ASSERT_TRUE(runs) << runs.GetError().message;
  EXPECT_EQ(runs.Value()[0].scenario.truths[0].boundReasons.at("maxLateral"),
            "1% of the friction force across the path");
}

TEST(ScenarioSet, BoxLandingNeedsADynamicBoxGravityAndARestInsideTheRun) {
  json landing = {{"kind", "box_landing"}, {"body", "hull"}, {"floor", 0}, {"restAfter", 0.05}};
  for (const char* name : {"maxFaceAngle", "maxMotion", "maxEnergyRise", "maxPenetration"}) {
    landing[name] = {{"value", 0.01}, {"reason", "one slop"}};
  }
  ExpectRefused(landing, "/truths/0/body: box_landing needs a dynamic box body");
  landing["body"] = "box";
  landing["restAfter"] = 0.2;  // the run is 10 steps of 0.01 s
  ExpectRefused(landing, "/truths/0/restAfter: is after the end of the run");
  landing["restAfter"] = 0.05;
  landing["maxFaceAngle"]["value"] = 1.0;
  ExpectRefused(landing, "/truths/0/maxFaceAngle/value: must be <= 0.785");
  landing["maxFaceAngle"]["value"] = 0.01;
  json doc = SlideDoc();
  doc["truths"][0] = WithTolerance(landing);
  ASSERT_TRUE(ParseScenarioText(doc.dump(), "t.json"));
  doc["world"]["gravity"] = {0, 0, 0};
  EXPECT_NE(Refusal(doc).find("/truths/0/kind: box_landing needs gravity"), std::string::npos);
}

TEST(ScenarioSet, BadPerTargetSweepsAreRefused) {
  json doc = SlideDoc();
  doc["sweeps"] = {{{"name", "mu"},
                    {"targets", {"/truths/0/mu", "/truths/0/v0"}},
                    {"perTarget", true},
                    {"values", {{0.3, 1}, {0.5}}}}};
  std::string message = Refusal(doc);
  EXPECT_NE(message.find("/sweeps/0/values/1: a perTarget value must be an array of 2 entries"),
            std::string::npos)
      << message;
  doc["sweeps"][0]["values"] = {{0.3, 1}, {0.5, 2}};
  doc["sweeps"][0]["labels"] = {"low"};
  message = Refusal(doc);
  EXPECT_NE(message.find("/sweeps/0/labels: needs one label per value (2)"), std::string::npos) << message;
  doc["sweeps"][0]["labels"] = {"low", "high"};
  auto runs = ParseScenarioText(doc.dump(), "t.json");
  ASSERT_TRUE(runs) << runs.GetError().message;
  ASSERT_EQ(runs.Value().size(), 2u);
  EXPECT_EQ(runs.Value()[1].id, "t[mu=high]");
  const auto& truth = std::get<SlidingStopTruth>(runs.Value()[1].scenario.truths[0].kind);
  EXPECT_EQ(truth.mu, 0.5);
  EXPECT_EQ(truth.v0, 2.0);
  doc["sweeps"][0]["values"] = {{0.3, 1}, {-0.5, 2}};
  message = Refusal(doc);
  EXPECT_NE(message.find("t.json (mu=high): /truths/0/mu: must be > 0"), std::string::npos) << message;
}

}  // namespace scenario_set_test
}  // namespace talus::harness
