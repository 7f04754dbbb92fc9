// Running a reference scene through a backend (see talus/harness/scenes/bench_run.h).
//
// The loop is: build the world (untimed), then for each step time its
// Step() calls alone (one per substep), read the contact count, and keep the
// few states the figures need (the pyramid's horizontal positions at the
// drift start step). The figures at the last step are read once the loop
// ends. The cost is the sum of the timed calls: no median over steps.
#include "talus/harness/scenes/bench_run.h"

#include "talus/harness/scenes/bench_perturb.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace talus::harness {
namespace {

int CountDynamicBodies(const Scenario& scene) {
  return static_cast<int>(std::count_if(scene.bodies.begin(), scene.bodies.end(),
                                        [](const BodySpec& body) { return body.motion == Motion::Dynamic; }));
}

// Horizontal (x, z) centres of mass of the first `count` bodies.
std::vector<Vec3> HorizontalCenters(const Backend& backend, int count) {
  std::vector<Vec3> centers(static_cast<size_t>(count));
  for (int index = 0; index < count; ++index) {
    Vec3 center = backend.GetBodyState(index).centerOfMass;
    center.y() = 0.0;
    centers[static_cast<size_t>(index)] = center;
  }
  return centers;
}

std::string Join(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

// Each stage's total and longest step over the run, in the engine's stage
// order. A step of several substeps adds up its substeps' timings first.
class StageRecorder {
 public:
  // Adds one backend step's timings to the current scene step, or says why
  // not: the stages must be those of the first step.
  std::optional<Error> Add(const std::vector<StageTiming>& timings, int step) {
    if (m_names.empty() && step == 1) {
      for (const StageTiming& t : timings) m_names.push_back(t.stage);
      m_stepMs.assign(m_names.size(), 0.0);
      m_totalMs.assign(m_names.size(), 0.0);
      m_maxMs.assign(m_names.size(), 0.0);
    }
    bool same = timings.size() == m_names.size();
    for (std::size_t i = 0; same && i < timings.size(); ++i) same = timings[i].stage == m_names[i];
    if (!same) {
      std::vector<std::string> names;
      for (const StageTiming& t : timings) names.push_back(t.stage);
      return Error{"step " + std::to_string(step) + ": the backend's stage timings (" + Join(names) +
                   ") are not those of step 1 (" + Join(m_names) + ")"};
    }
    for (std::size_t i = 0; i < timings.size(); ++i) m_stepMs[i] += timings[i].seconds * 1e3;
    return std::nullopt;
  }

  // Closes the scene step: its stage times go into the totals and maxima.
  void EndStep() {
    for (std::size_t i = 0; i < m_names.size(); ++i) {
      m_totalMs[i] += m_stepMs[i];
      m_maxMs[i] = std::max(m_maxMs[i], m_stepMs[i]);
      m_stepMs[i] = 0.0;
    }
  }

  std::vector<BenchStage> Stages(int steps) const {
    std::vector<BenchStage> stages;
    for (std::size_t i = 0; i < m_names.size(); ++i) {
      stages.push_back({m_names[i], m_totalMs[i] / static_cast<double>(steps), m_maxMs[i]});
    }
    return stages;
  }

 private:
  std::vector<std::string> m_names;
  std::vector<double> m_stepMs;   // per stage, this scene step so far
  std::vector<double> m_totalMs;  // per stage, over the run
  std::vector<double> m_maxMs;    // per stage, the longest scene step
};

// The hull pile's figures at the end of a run.
void MeasureHullPile(const Backend& backend, const Scenario& scene, int dynamicBodies, int side,
                     BenchReport& report) {
  double deepest = 0.0;
  for (const ContactReading& contact : backend.GetContacts()) deepest = std::max(deepest, contact.depth);
  report.maxPenetration = deepest;
  report.kineticEnergy = MeasureWorld(backend, scene.world.gravity).kineticEnergy;
  const double w = HullPileWallInnerHalfWidth(side);
  int escaped = 0;
  for (int index = 0; index < dynamicBodies; ++index) {
    const Vec3 c = backend.GetBodyState(index).centerOfMass;
    // Written so that a NaN centre counts as escaped.
    const bool inside = c.y() >= 0.0 && std::abs(c.x()) <= w && std::abs(c.z()) <= w;
    if (!inside) ++escaped;
  }
  report.escaped = escaped;
}

}  // namespace

std::optional<std::string> BenchSkipReason(std::string_view engine, int dynamicBodies) {
  // Only the defaults collide every pair (dSimpleSpace); "-tuned" uses dHashSpace.
  const bool allPairs = engine.substr(0, 4) == "ode-" && !engine.ends_with("-tuned");
  if (engine.substr(0, 8) == "ode-step" && dynamicBodies > kOdeStepMaxBodies) {
    return "dWorldStep solves each island as one dense LCP (memory ~ rows^2, time up to rows^3); " +
           std::to_string(dynamicBodies) + " bodies > " + std::to_string(kOdeStepMaxBodies) +
           " (kOdeStepMaxBodies)";
  }
  if (allPairs && dynamicBodies > kOdeMaxBodies) {
    return "the ODE backend's dSimpleSpace tests all n^2/2 pairs every step; " +
           std::to_string(dynamicBodies) + " bodies > " + std::to_string(kOdeMaxBodies) + " (kOdeMaxBodies)";
  }
  if (engine.substr(0, 6) == "mujoco" && dynamicBodies > kMujocoMaxBodies) {
    return "MuJoCo 2.2.2 preallocates its constraint arrays as njmax x njmax (memory ~ bodies^2, over 1 "
           "GB); " +
           std::to_string(dynamicBodies) + " bodies > " + std::to_string(kMujocoMaxBodies) +
           " (kMujocoMaxBodies). Measured ~13 contacts per cube: pyramid H = 10 needs njmax ~20,000 rows, "
           "efc_AR alone 4.8 GB whatever the solver or cone, at ~7 s per step (docs/testbed-backends.md)";
  }
  return std::nullopt;
}

std::optional<std::string> BenchSolverProblem(std::string_view engine, const BenchSolver& solver) {
  if (solver.iterations < 0 || solver.iterations > kBenchMaxIterations) {
    return "iterations " + std::to_string(solver.iterations) + ": must be in [0, " +
           std::to_string(kBenchMaxIterations) + "] (0: the engine's default)";
  }
  if (solver.substeps < 1 || solver.substeps > kBenchMaxSubsteps) {
    return "substeps " + std::to_string(solver.substeps) + ": must be in [1, " +
           std::to_string(kBenchMaxSubsteps) + "]";
  }
  if (solver.iterations > 0 && engine.substr(0, 8) == "ode-step") {
    return "iterations " + std::to_string(solver.iterations) + ": " + std::string(engine) +
           " has no iteration count (dWorldStep solves each island directly, a Dantzig LCP)";
  }
  return std::nullopt;
}

std::string BenchSolverLabel(const BenchSolver& solver) {
  std::string label = solver.iterations == 0 ? std::string("engine default")
                                             : std::to_string(solver.iterations) + " iterations";
  if (solver.substeps > 1) label += ", " + std::to_string(solver.substeps) + " substeps";
  return label;
}

namespace {

// The scene at `parameter`, its dynamic bodies moved by the perturbation
// when there is one.
Result<Scenario> BuildBenchScenario(const BenchScene& scene, int parameter,
                                    const std::optional<BenchPerturbation>& perturbation) {
  auto built = scene.make(parameter);
  if (!built) return built.GetError();
  if (perturbation) {
    built = PerturbDynamicPositions(std::move(built.Value()), perturbation->amount, perturbation->seed);
    if (!built) return built.GetError();
  }
  return built;
}

// The run a backend is created for: the scenario at h / N for N substeps.
Run MakeBenchRun(const Scenario& scenario, int steps, const BenchSolver& solver) {
  Run run;
  run.id = scenario.name;
  run.scenario = scenario;
  // Substeps: every engine steps N times with h / N (none of the backends
  // exposes a substep setting of its own; Bullet's stepSimulation(h, N,
  // h / N) would take the same N internal steps).
  run.timeStep = scenario.world.timeStep / solver.substeps;
  run.iterations = solver.iterations != 0 ? solver.iterations : scenario.world.iterations;
  run.steps = steps * solver.substeps;
  return run;
}

// Steps the backend `steps` times (each its substeps, timed as one) and
// records the times, the stages and the contact count in `report`. The
// pyramid's horizontal centres at the drift's start step are returned
// (empty for other scenes).
Result<std::vector<Vec3>> RunTimedSteps(Backend& backend, const BenchScene& scene, int steps,
                                        const BenchSolver& solver, const BenchProgress& progress,
                                        BenchReport& report) {
  const int driftStart = std::min(kPyramidDriftStartStep, steps);
  std::vector<Vec3> startCenters;
  StageRecorder stages;
  double totalMs = 0.0;
  double longestMs = 0.0;
  for (int step = 1; step <= steps; ++step) {
    double stepMs = 0.0;
    for (int substep = 0; substep < solver.substeps; ++substep) {
      const auto begin = std::chrono::steady_clock::now();
      backend.Step();
      const auto end = std::chrono::steady_clock::now();
      stepMs += std::chrono::duration<double, std::milli>(end - begin).count();
      if (auto refused = stages.Add(backend.StageTimings(), step)) return *refused;
    }
    stages.EndStep();
    totalMs += stepMs;
    longestMs = std::max(longestMs, stepMs);
    report.maxContacts = std::max(report.maxContacts, static_cast<int>(backend.GetContacts().size()));
    if (scene.kind == BenchSceneKind::Pyramid && step == driftStart) {
      startCenters = HorizontalCenters(backend, report.bodies);
    }
    if (progress) progress(step, steps);
  }
  report.totalMs = totalMs;
  report.msMean = totalMs / static_cast<double>(steps);
  report.msMax = longestMs;
  report.stages = stages.Stages(steps);
  return startCenters;
}

// The pyramid's drift: the largest horizontal move of a body's centre
// since the start step, NaN when a body exploded.
double PyramidDrift(const Backend& backend, int dynamicBodies, const std::vector<Vec3>& startCenters) {
  const std::vector<Vec3> endCenters = HorizontalCenters(backend, dynamicBodies);
  double drift = 0.0;
  for (size_t index = 0; index < endCenters.size(); ++index) {
    const double moved = (endCenters[index] - startCenters[index]).norm();
    // A NaN distance (an exploded body) must not hide behind std::max.
    drift = std::isnan(moved) ? moved : std::max(drift, moved);
    if (std::isnan(drift)) break;
  }
  return drift;
}

}  // namespace

Result<BenchReport> RunBenchScene(const BackendRegistry& registry, std::string_view engine,
                                  const BenchScene& scene, int parameter, int steps,
                                  const BenchProgress& progress,
                                  const std::optional<BenchPerturbation>& perturbation,
                                  const BenchSolver& solver) {
  if (steps < 1) return Error{"steps = " + std::to_string(steps) + ": must be >= 1"};
  if (auto problem = BenchSolverProblem(engine, solver)) return Error{*problem};
  auto built = BuildBenchScenario(scene, parameter, perturbation);
  if (!built) return built.GetError();
  const Scenario& scenario = built.Value();
  const int dynamicBodies = CountDynamicBodies(scenario);

  BenchReport report;
  report.engine = std::string(engine);
  report.scene = std::string(scene.name);
  report.parameter = parameter;
  report.bodies = dynamicBodies;
  report.steps = steps;
  report.solver = solver;
  report.perturbation = perturbation;
  if (!registry.Has(engine)) {
    // Let the registry word the error (it lists the known names).
    Run none;
    return registry.Create(engine, none).GetError();
  }
  if (auto reason = BenchSkipReason(engine, dynamicBodies)) {
    report.skipped = *reason;
    return report;
  }

  const Run run = MakeBenchRun(scenario, steps, solver);
  auto created = registry.Create(engine, run);
  if (!created) return created.GetError();
  Backend& backend = *created.Value();
  backend.TimeStages();
  auto startCenters = RunTimedSteps(backend, scene, steps, solver, progress, report);
  if (!startCenters) return startCenters.GetError();
  if (scene.kind == BenchSceneKind::Pyramid) {
    report.drift = PyramidDrift(backend, dynamicBodies, startCenters.Value());
  } else {
    MeasureHullPile(backend, scenario, dynamicBodies, parameter, report);
  }
  return report;
}

}  // namespace talus::harness
