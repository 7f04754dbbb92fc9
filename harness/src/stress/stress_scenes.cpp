// The worlds of the stress axes (stress.h StressRuns), built in code so
// every backend runs the same world. Conventions: +y up, a static ground
// box whose top face is y = 0 (scaled with the bodies where the axis
// scales them), boxes placed exactly touching (no initial gap or overlap).
#include <cmath>
#include <cstdio>

#include "support/text_util.h"
#include "talus/harness/stress/stress.h"

namespace talus::harness {
namespace {

BodySpec Box(std::string name, const Vec3& halfExtents, const Vec3& position, Motion motion) {
  BodySpec body;
  body.name = std::move(name);
  body.shape = BoxShape{halfExtents};
  body.motion = motion;
  body.position = position;
  return body;
}

BodySpec Ground(const Vec3& halfExtents, const Vec3& offset) {
  return Box("ground", halfExtents, offset + Vec3(0.0, -halfExtents.y(), 0.0), Motion::Static);
}

Run MakeRun(std::string name, double value, double timeStep, int steps, std::vector<BodySpec> bodies) {
  Run run;
  run.id = Concat({name, "[", FormatNumber(value), "]"});
  run.scenario.name = name;
  run.scenario.world.timeStep = timeStep;
  run.scenario.world.steps = steps;
  run.scenario.bodies = std::move(bodies);
  run.scenario.measure = {Quantity::Position, Quantity::Velocity, Quantity::Energy};
  run.timeStep = timeStep;
  run.steps = steps;
  return run;
}

int StepsFor(double seconds, double timeStep) {
  return std::max(1, static_cast<int>(std::lround(seconds / timeStep)));
}

// A cube of edge `edge` resting on the ground at `offset` (3 s at 1/60 s):
// its centre of mass settles at edge / 2 within 1 % of the edge.
Run RestRun(const std::string& name, double value, double edge, const Vec3& offset) {
  std::vector<BodySpec> bodies{Ground(Vec3(10.0, 0.5, 10.0) * edge, offset)};
  bodies.push_back(
      Box("box", Vec3::Constant(edge / 2.0), offset + Vec3(0.0, edge / 2.0, 0.0), Motion::Dynamic));
  bodies.back().density = 1000.0;
  Run run = MakeRun(name + "_rest", value, 1.0 / 60.0, 180, std::move(bodies));
  Truth truth;
  truth.kind = RestHeightTruth{edge / 2.0, 1e-3 * edge};
  truth.body = 1;
  truth.tolerance.absolute = 0.01 * edge;
  run.scenario.truths.push_back(truth);
  return run;
}

// The same cube launched along +x at 3 sqrt(edge) m/s with mu = 0.5 (the
// combined value) at 1/240 s: it stops after v0^2 / (2 mu g), within 3 %.
Run SlideRun(const std::string& name, double value, double edge, const Vec3& offset) {
  const double v0 = 3.0 * std::sqrt(edge);
  std::vector<BodySpec> bodies{Ground(Vec3(20.0, 0.5, 20.0) * edge, offset)};
  bodies.push_back(
      Box("box", Vec3::Constant(edge / 2.0), offset + Vec3(0.0, edge / 2.0, 0.0), Motion::Dynamic));
  bodies.back().density = 1000.0;
  bodies.back().linearVelocity = Vec3(v0, 0.0, 0.0);
  const double timeStep = 1.0 / 240.0;
  Run run = MakeRun(name + "_slide", value, timeStep,
                    StepsFor(std::max(0.5, 2.5 * std::sqrt(edge)), timeStep), std::move(bodies));
  Truth truth;
  SlidingStopTruth slide;
  slide.v0 = v0;
  slide.mu = 0.5;
  slide.maxLateral = 0.01 * edge;
  truth.kind = slide;
  truth.body = 1;
  truth.tolerance.relative = 0.03;
  run.scenario.truths.push_back(truth);
  return run;
}

}  // namespace

std::vector<Run> StressRuns(StressAxis axis, double value) {
  const Vec3 unitBox = Vec3::Constant(0.5);
  switch (axis) {
    case StressAxis::Column: {
      // `value` 1 m cubes of 1 kg on each other, 10 s at 1/60 s.
      std::vector<BodySpec> bodies{Ground(Vec3(10.0, 0.5, 10.0), Vec3::Zero())};
      const int count = static_cast<int>(std::lround(value));
      for (int k = 0; k < count; ++k) {
        bodies.push_back(
            Box(Concat({"box", std::to_string(k)}), unitBox, Vec3(0.0, 0.5 + k, 0.0), Motion::Dynamic));
        bodies.back().mass = 1.0;
      }
      return {MakeRun("column", value, 1.0 / 60.0, 600, std::move(bodies))};
    }
    case StressAxis::MassRatio: {
      // Two 1 m cubes, 1 kg below and `value` kg on top, 5 s at 1/60 s.
      std::vector<BodySpec> bodies{Ground(Vec3(10.0, 0.5, 10.0), Vec3::Zero())};
      bodies.push_back(Box("bottom", unitBox, Vec3(0.0, 0.5, 0.0), Motion::Dynamic));
      bodies.back().mass = 1.0;
      bodies.push_back(Box("top", unitBox, Vec3(0.0, 1.5, 0.0), Motion::Dynamic));
      bodies.back().mass = value;
      return {MakeRun("mass_ratio", value, 1.0 / 60.0, 300, std::move(bodies))};
    }
    case StressAxis::TimeStep: {
      // A 5-layer pyramid of 1 m cubes of 1 kg, 5 cm apart in a layer, for 5 s.
      constexpr int kLayers = 5;
      std::vector<BodySpec> bodies{Ground(Vec3(10.0, 0.5, 10.0), Vec3::Zero())};
      for (int layer = 0; layer < kLayers; ++layer) {
        const int count = kLayers - layer;
        for (int i = 0; i < count; ++i) {
          const double x = (i - (count - 1) / 2.0) * 1.05;
          bodies.push_back(Box(Concat({"box", std::to_string(layer), "_", std::to_string(i)}), unitBox,
                               Vec3(x, 0.5 + layer, 0.0), Motion::Dynamic));
          bodies.back().mass = 1.0;
        }
      }
      return {MakeRun("pyramid", value, value, StepsFor(5.0, value), std::move(bodies))};
    }
    case StressAxis::Offset: {
      // The rest and slide worlds moved `value` metres along x and z.
      const Vec3 offset(value, 0.0, value);
      return {RestRun("offset", value, 1.0, offset), SlideRun("offset", value, 0.5, offset)};
    }
    case StressAxis::Speed: {
      // No gravity: a 0.1 m cube of 1 kg 0.5 m before a static wall 0.05 m
      // thick (x in [-0.025, 0.025]), launched at `value` m/s, at 1/60 s, run
      // until it would be 0.5 m past the wall plus 0.5 s.
      std::vector<BodySpec> bodies{Box("wall", Vec3(0.025, 1.0, 1.0), Vec3::Zero(), Motion::Static)};
      bodies.push_back(Box("box", Vec3::Constant(0.05), Vec3(-0.5, 0.0, 0.0), Motion::Dynamic));
      bodies.back().mass = 1.0;
      bodies.back().linearVelocity = Vec3(value, 0.0, 0.0);
      const double timeStep = 1.0 / 60.0;
      Run run = MakeRun("tunnel", value, timeStep, StepsFor(1.0 / value + 0.5, timeStep), std::move(bodies));
      run.scenario.world.gravity = Vec3::Zero();
      return {run};
    }
    case StressAxis::EnergyDrift: {
      // No gravity: a 1 x 0.6 x 0.4 m box of 1 kg spinning at (0.2, 0.1, 3)
      // rad/s (mostly about its axis of largest inertia, z), `value` steps
      // of 1/60 s.
      std::vector<BodySpec> bodies{Box("box", Vec3(0.5, 0.3, 0.2), Vec3::Zero(), Motion::Dynamic)};
      bodies.back().mass = 1.0;
      bodies.back().angularVelocity = Vec3(0.2, 0.1, 3.0);
      Run run = MakeRun("spin", value, 1.0 / 60.0, static_cast<int>(std::lround(value)), std::move(bodies));
      run.scenario.world.gravity = Vec3::Zero();
      return {run};
    }
    case StressAxis::SmallSize:
    case StressAxis::LargeSize:
      return {RestRun("size", value, value, Vec3::Zero()), SlideRun("size", value, value, Vec3::Zero())};
  }
  return {};
}

}  // namespace talus::harness
