// The Talus backend: builds a talus::World from a Run and reads it back.
//
// Mapping: every scenario body becomes one World body, created in scenario
// order, whose frame is the scenario body frame (position, orientation);
// the shape is written in that frame (boxes and spheres centred on it, hulls
// from BuildHull on the file's points); the centre of mass and the inertia
// about it come from ComputeBodyMass, given as localCenterOfMass and
// localInertia (body axes), so the engine and the peers agree on mass data
// to the last bit. Contacts come from World::GetContactPoints (public API):
// one point per manifold point, normal from B to A, depth > 0 when overlapping.
#include "talus/reference/talus_backend.h"
#include "talus/reference/setting_text.h"

#include <algorithm>
#include <cassert>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "talus/body.h"
#include "talus/harness/scenario/applied_loads.h"
#include "talus/hull_builder.h"
#include "talus/reference/body_mass.h"
#include "talus/shape.h"
#include "talus/step_stage.h"
#include "talus/world.h"

namespace talus::reference {
namespace {

using harness::BodySpec;
using harness::CombineRule;
using harness::Run;

/// Which engine options a variant uses.
enum class Variant { Defaults, WriteUp, SplitImpulses, Coloured, Soft };

const char* VariantName(Variant variant) {
  switch (variant) {
    case Variant::Defaults:
      return "talus";
    case Variant::WriteUp:
      return "talus-writeup";
    case Variant::SplitImpulses:
      return "talus-split";
    case Variant::Coloured:
      return "talus-coloured";
    case Variant::Soft:
      return "talus-soft";
  }
  return "talus";
}

Result<FrictionCombine> ToFrictionCombine(CombineRule rule) {
  switch (rule) {
    case CombineRule::Sqrt:
      return FrictionCombine::GeometricMean;
    case CombineRule::Min:
      return FrictionCombine::Min;
    case CombineRule::Max:
      return FrictionCombine::Max;
    case CombineRule::Multiply:
      return FrictionCombine::Product;
    case CombineRule::Average:
      return FrictionCombine::Average;
  }
  return Error{"unknown friction combine rule"};
}

Result<RestitutionCombine> ToRestitutionCombine(CombineRule rule) {
  switch (rule) {
    case CombineRule::Max:
      return RestitutionCombine::Max;
    case CombineRule::Min:
      return RestitutionCombine::Min;
    case CombineRule::Multiply:
      return RestitutionCombine::Product;
    case CombineRule::Average:
      return RestitutionCombine::Average;
    case CombineRule::Sqrt:
      break;
  }
  return Error{std::string("restitution combine \"") + harness::CombineRuleName(rule) +
               "\" has no Talus rule (max, min, multiply, average)"};
}

Result<Shape> MakeShape(const BodySpec& spec) {
  if (const auto* box = std::get_if<harness::BoxShape>(&spec.shape))
    return Shape::CreateBox(box->halfExtents);
  if (const auto* sphere = std::get_if<harness::SphereShape>(&spec.shape)) {
    return Shape::CreateSphere(sphere->radius);
  }
  const auto& points = std::get<harness::HullShape>(spec.shape).points;
  auto hull = BuildHull(points);
  if (!hull) return hull.GetError();
  return Shape::CreateHull(std::make_shared<const Hull>(std::move(hull).Value()));
}

class TalusBackend final : public harness::Backend {
 public:
  static Result<std::unique_ptr<harness::Backend>> Create(const Run& run, Variant variant,
                                                          const TalusBackendOptions& options);

  [[nodiscard]] std::string Name() const override { return VariantName(m_variant); }
  void Step() override;
  [[nodiscard]] int BodyCount() const override { return static_cast<int>(m_bodies.size()); }
  [[nodiscard]] harness::BodyReading GetBodyState(int index) const override;
  [[nodiscard]] std::vector<harness::ContactReading> GetContacts() const override;
  [[nodiscard]] std::vector<harness::Setting> Settings() const override { return m_settings; }
  [[nodiscard]] std::vector<harness::StepCounter> StepCounters() const override;
  [[nodiscard]] std::vector<harness::StageTiming> StageTimings() const override;
  void TimeStages() override;
  [[nodiscard]] std::string StepFailure() const override { return m_failure; }

 private:
  TalusBackend(World world, Variant variant) : m_world(std::move(world)), m_variant(variant) {}
  void AddSettings(const Run& run, const WorldSettings& base);
  // Applies this step's impulses and loads; why one was refused, else "".
  std::string ApplyLoads();

  World m_world;
  Variant m_variant;
  double m_timeStep = 0.0;
  std::vector<BodyId> m_bodies;               // by scenario index
  std::vector<int> m_scenarioIndexOfSlot;     // world body index -> scenario index
  std::vector<BodyMass> m_masses;             // by scenario index
  std::vector<harness::Setting> m_settings;   // fixed at creation
  StepStatistics m_lastStep;                  // counters of the last Step (zero before the first)
  std::string m_failure;                      // World::Step's refusal of the last step; empty when it ran
  std::vector<harness::AppliedLoad> m_loads;  // the scenario's, applied each step
  std::vector<harness::AppliedImpulse> m_impulses;  // the scenario's, each at its step
  long long m_stepIndex = 0;                        // steps taken
};

// The structure's name as the settings and the report's figure 2 show it.
const char* BroadPhaseName(BroadPhaseKind kind) {
  switch (kind) {
    case BroadPhaseKind::UniformGrid:
      return "uniform grid";
    case BroadPhaseKind::AabbTree:
      return "AABB tree";
    case BroadPhaseKind::BruteForce:
      return "brute force";
  }
  return "unknown";
}

const char* PositionCorrectionName(PositionCorrection correction) {
  switch (correction) {
    case PositionCorrection::Baumgarte:
      return "Baumgarte";
    case PositionCorrection::SplitImpulses:
      return "split impulses";
  }
  return "unknown";
}

// A setting of the engine as text: `value` is this row's, `scenarioDefault`
// the engine's default as the scenario poses it (ScenarioSettings). When the
// row departs from it, the default and `effect` (why, and what it measurably
// changes) are recorded beside it.
harness::Setting Choice(std::string key, std::string value, std::string scenarioDefault, std::string effect) {
  if (value == scenarioDefault) return {std::move(key), std::move(value)};
  return {std::move(key), std::move(value), std::move(scenarioDefault), std::move(effect)};
}

std::string TranslationText(TranslationIntegrator translation) {
  return translation == TranslationIntegrator::SymplecticEuler
             ? "symplectic Euler (v += h a; x += h v)"
             : "v += h a; x += h (v0 + v) / 2 for a body no impulse touched (exact for constant "
               "acceleration), else x += h v";
}

std::string SolverText(const WorldSettings& s) {
  if (s.methods.stepSolver == StepSolver::SoftStep) {
    const SoftStepSettings& soft = s.methods.softStep;
    return "soft step: " + std::to_string(soft.substeps) + " sub-steps, contacts at " +
           SettingNumber(soft.contactHertz) + " Hz (at most a quarter of the sub-step rate), damping ratio " +
           SettingNumber(soft.dampingRatio) + ", push-out " + SettingNumber(soft.pushOutSpeed) +
           " m/s; the sweep settings below are unused";
  }
  return s.methods.contactOrder == ContactOrder::PairByPair
             ? "sequential impulses (scalar, pair order)"
             : "sequential impulses, coloured, four pairs per SIMD bundle";
}

std::string FrictionSolveText(FrictionSolve friction) {
  return friction == FrictionSolve::PerPoint
             ? "per point (two rows a point, one after another)"
             : "coupled block: a sticking pair's normals and friction (slip and spin patterns) solved "
               "together, else per point";
}

std::string ExtraSweepsText(const WorldSettings& s) {
  if (s.methods.maxVelocityIterations <= s.velocityIterations) return "none";
  return "up to " + std::to_string(s.methods.maxVelocityIterations) + " sweeps, until changes < " +
         SettingNumber(s.methods.velocityTolerance) + " m/s";
}

std::string BounceTimingText(BounceTiming timing) {
  return timing == BounceTiming::TimeOfImpact
             ? "time of impact inside the step (reflected flight to the step's end)"
             : "step boundary (the write-up's)";
}

std::string SatText(SatMode mode) {
  return mode == SatMode::Full ? "full (every face and edge pair)" : "Gauss-map pruned edge pairs";
}

std::string ManifoldText(ManifoldMode mode) {
  return mode == ManifoldMode::WriteUp ? "write-up (vertices near the contact plane, one depth)"
                                       : "clipped incident face, reduced to 4 points";
}

std::string ReuseText(double distance) { return distance > 0.0 ? SettingNumber(distance) : "off"; }

std::string PersistenceText(const NarrowPhaseSettings& n) {
  return n.persistence == ManifoldPersistence::Accumulate ? SettingNumber(n.persistenceDistance) : "off";
}

std::string SpeculativeMarginText(const WorldSettings& s) {
  const std::string fixed = SettingNumber(s.methods.narrowPhase.speculativeMargin);
  if (!s.methods.speculativeMotion) return fixed + " (fixed)";
  return fixed + ", or the pair's reach this step where larger (h (|v| + |w| rho + g h) of each body)";
}

std::string GyroscopicText(RotationIntegrator rotation) {
  switch (rotation) {
    case RotationIntegrator::ConstantRate:
      return "off (MethodSettings::rotation = ConstantRate)";
    case RotationIntegrator::MomentumSplitting:
      return "on (MethodSettings::rotation = MomentumSplitting: L kept, exact rotations about the "
             "principal axes)";
    case RotationIntegrator::MomentumSplittingFourthOrder:
      return "on (MethodSettings::rotation = MomentumSplittingFourthOrder: L kept, exact rotations about "
             "the principal axes, fourth order)";
  }
  return "unknown";
}

// What the scenario states, on top of WorldSettings{}: the user's choices
// (gravity, iterations, combine rules, sleeping off as the peers run, the
// gyroscopic term, the broad phase, the bounce timing when the file names
// one) and the thread count of the run. The `talus` row is exactly this.
WorldSettings ScenarioSettings(const Run& run, FrictionCombine friction, RestitutionCombine restitution,
                               const TalusBackendOptions& options) {
  WorldSettings settings;
  settings.threads = options.threads;
  settings.gravity = run.scenario.world.gravity;
  if (run.iterations > 0) {
    settings.velocityIterations = run.iterations;
    settings.positionIterations = run.iterations;
  }
  settings.frictionCombine = friction;
  settings.restitutionCombine = restitution;
  settings.sleeping = false;
  // The scenario's gyroscopic term: on, the engine's default rotation;
  // off, the write-up's constant rate.
  if (!run.scenario.world.gyroscopic) settings.methods.rotation = RotationIntegrator::ConstantRate;
  // The scenario's broad phase: auto keeps the engine's default (the grid,
  // brute force in tiny worlds); any other choice runs in every world.
  switch (run.scenario.world.broadPhase) {
    case harness::BroadPhaseChoice::Auto:
      break;
    case harness::BroadPhaseChoice::UniformGrid:
      settings.broadPhase = BroadPhaseKind::UniformGrid;
      settings.methods.forceBroadPhase = true;
      break;
    case harness::BroadPhaseChoice::AabbTree:
      settings.broadPhase = BroadPhaseKind::AabbTree;
      settings.methods.forceBroadPhase = true;
      break;
    case harness::BroadPhaseChoice::BruteForce:
      settings.broadPhase = BroadPhaseKind::BruteForce;
      settings.methods.forceBroadPhase = true;
      break;
  }
  // The scenario's bounce timing; auto keeps the engine's default.
  switch (run.scenario.world.bounceTiming) {
    case harness::BounceTimingChoice::Auto:
      break;
    case harness::BounceTimingChoice::TimeOfImpact:
      settings.methods.bounceTiming = BounceTiming::TimeOfImpact;
      break;
    case harness::BounceTimingChoice::StepBoundary:
      settings.methods.bounceTiming = BounceTiming::StepBoundary;
      break;
  }
  return settings;
}

// The write-up's choices (docs/write-up.md) in place of each improvement
// the engine's defaults carry; the scenario's own choices stay, but for a
// bounce timing left to auto, which is the write-up's step boundary.
void ApplyWriteUp(const Run& run, WorldSettings& settings) {
  if (run.scenario.world.gyroscopic) {
    // The second-order splitting: the write-up has no gyroscopic term, and
    // the scenario asks for one; the least of the engine's.
    settings.methods.rotation = RotationIntegrator::MomentumSplitting;
  }
  if (run.scenario.world.bounceTiming == harness::BounceTimingChoice::Auto) {
    settings.methods.bounceTiming = BounceTiming::StepBoundary;
  }
  settings.methods.translation = TranslationIntegrator::SymplecticEuler;
  settings.methods.narrowPhase.satMode = SatMode::Full;
  settings.methods.narrowPhase.manifoldMode = ManifoldMode::WriteUp;
  settings.methods.narrowPhase.useSatCache = false;
  settings.methods.narrowPhase.reuseDistance = 0.0;                       // the narrow phase every step
  settings.methods.narrowPhase.persistence = ManifoldPersistence::Fresh;  // and only its points
  settings.methods.speculativeMotion = false;                             // a fixed speculative margin
  settings.methods.warmStarting = false;
  // Plain row-by-row Gauss-Seidel, a fixed number of sweeps (a cap below
  // the iteration count means no extra sweeps), friction per point.
  settings.methods.blockSolver = false;
  settings.methods.maxVelocityIterations = 1;
  settings.methods.frictionSolve = FrictionSolve::PerPoint;
  settings.methods.shockPropagation = false;  // the sweeps alone
}

// The variant's settings: the scenario's on WorldSettings{}, then the
// variant's named differences (listed in docs/testbed-backends.md, "The
// Talus rows", and in each row's settings as engine-default departures).
WorldSettings MakeSettings(const WorldSettings& base, const Run& run, Variant variant) {
  WorldSettings settings = base;
  switch (variant) {
    case Variant::Defaults:
      break;
    case Variant::WriteUp:
      ApplyWriteUp(run, settings);
      break;
    case Variant::SplitImpulses:
      settings.methods.positionCorrection = PositionCorrection::SplitImpulses;
      break;
    case Variant::Coloured:
      // The coloured order, with the friction rows it has (no coupled block).
      settings.methods.contactOrder = ContactOrder::ByColour;
      settings.methods.frictionSolve = FrictionSolve::PerPoint;
      break;
    case Variant::Soft:
      // The soft step (docs/dynamics.md, "The soft step") at the engine's
      // 4 sub-steps; the run's iterations are a sweep count, which this
      // solver does not have. Its friction rows are per point (it has no
      // coupled block).
      settings.methods.stepSolver = StepSolver::SoftStep;
      settings.methods.frictionSolve = FrictionSolve::PerPoint;
      break;
  }
  return settings;
}

// A row's settings and the scenario's on WorldSettings{} they depart from.
struct RowSettings {
  WorldSettings base;
  WorldSettings settings;
};

Result<RowSettings> ConfigureRow(const Run& run, Variant variant, const TalusBackendOptions& options) {
  const std::string prefix = std::string(VariantName(variant)) + ": ";
  auto friction = ToFrictionCombine(run.scenario.world.frictionCombine);
  if (!friction) return Error{prefix + friction.GetError().message};
  auto restitution = ToRestitutionCombine(run.scenario.world.restitutionCombine);
  if (!restitution) return Error{prefix + restitution.GetError().message};
  RowSettings row;
  row.base = ScenarioSettings(run, friction.Value(), restitution.Value(), options);
  row.settings = MakeSettings(row.base, run, variant);
  return row;
}

Result<std::unique_ptr<harness::Backend>> TalusBackend::Create(const Run& run, Variant variant,
                                                               const TalusBackendOptions& options) {
  const std::string prefix = std::string(VariantName(variant)) + ": ";
  auto row = ConfigureRow(run, variant, options);
  if (!row) return row.GetError();
  const WorldSettings& base = row.Value().base;
  auto world = World::Create(row.Value().settings);
  if (!world) return Error{prefix + world.GetError().message};

  std::unique_ptr<TalusBackend> backend(new TalusBackend(std::move(world).Value(), variant));
  backend->m_timeStep = run.timeStep;
  for (std::size_t i = 0; i < run.scenario.bodies.size(); ++i) {
    const BodySpec& spec = run.scenario.bodies[i];
    const std::string where = prefix + "body \"" + spec.name + "\": ";
    auto mass = ComputeBodyMass(spec);
    if (!mass) return Error{where + mass.GetError().message};
    auto shape = MakeShape(spec);
    if (!shape) return Error{where + shape.GetError().message};
    BodyDef def;
    def.type = spec.motion == harness::Motion::Dynamic     ? BodyType::Dynamic
               : spec.motion == harness::Motion::Kinematic ? BodyType::Kinematic
                                                           : BodyType::Static;
    def.position = spec.position;
    def.orientation = spec.orientation;
    def.shape = std::move(shape).Value();
    def.friction = spec.friction;
    def.restitution = spec.restitution;
    def.allowSleep = false;
    if (def.type == BodyType::Kinematic) {
      // The engine's own kinematic body: moved by the prescribed velocity
      // each step, infinite mass to contacts. Its centre of mass is its
      // origin (no mass data), so the origin moves at linearVelocity.
      def.linearVelocity = spec.linearVelocity;
      def.angularVelocity = spec.angularVelocity;
    }
    if (def.type == BodyType::Dynamic) {
      def.linearVelocity = spec.linearVelocity;
      def.angularVelocity = spec.angularVelocity;
      def.density = 0.0;  // mass data below, shared with the peers
      def.mass = mass.Value().mass;
      def.localInertia = mass.Value().inertia;
      def.localCenterOfMass = mass.Value().centroid;
    }
    auto id = backend->m_world.CreateBody(def);
    if (!id) return Error{where + id.GetError().message};
    const auto slot = static_cast<std::size_t>(id.Value().index);
    if (backend->m_scenarioIndexOfSlot.size() <= slot) backend->m_scenarioIndexOfSlot.resize(slot + 1, -1);
    backend->m_scenarioIndexOfSlot[slot] = static_cast<int>(i);
    backend->m_bodies.push_back(id.Value());
    backend->m_masses.push_back(mass.Value());
  }
  backend->m_loads = run.scenario.loads;
  backend->m_impulses = run.scenario.impulses;
  backend->AddSettings(run, base);
  return std::unique_ptr<harness::Backend>(std::move(backend));
}

// The scenario's impulses due at this step and its loads' share of it,
// through the World's own calls: ApplyLinearImpulse changes the velocities
// at once, ApplyForce / ApplyTorque act over the next step only. Each
// vector was checked finite by the loader, but a body's pose may not be,
// so a refusal ends the run as a refused step does.
std::string TalusBackend::ApplyLoads() {
  const double t = static_cast<double>(m_stepIndex) * m_timeStep;
  for (const harness::AppliedImpulse& impulse : m_impulses) {
    if (!harness::AppliedImpulseAtStep(impulse, m_stepIndex, m_timeStep)) continue;
    const BodyId id = m_bodies[static_cast<std::size_t>(impulse.body)];
    const talus::BodyState state = m_world.GetBodyState(id).Value();
    const Vec3 point =
        harness::ImpulseWorldPoint(impulse, state.position, state.orientation).value_or(state.centerOfMass);
    if (auto applied = m_world.ApplyLinearImpulse(id, impulse.linear, point); !applied) {
      return applied.GetError().message;
    }
  }
  for (const harness::AppliedLoad& load : m_loads) {
    const double share = harness::AppliedLoadShare(load, t, m_timeStep);
    if (share == 0.0) continue;
    const BodyId id = m_bodies[static_cast<std::size_t>(load.body)];
    const talus::BodyState state = m_world.GetBodyState(id).Value();
    const harness::WorldLoad world = harness::ToWorldLoad(load, share, state.position, state.orientation);
    Status applied = world.point ? m_world.ApplyForce(id, world.force, *world.point)
                                 : m_world.ApplyForceToCenter(id, world.force);
    if (applied) applied = m_world.ApplyTorque(id, world.torque);
    if (!applied) return applied.GetError().message;
  }
  return {};
}

void TalusBackend::Step() {
  m_failure = ApplyLoads();
  if (!m_failure.empty()) return;
  ++m_stepIndex;
  // World::Step refuses a step it cannot take (a body beyond its 1e9 m
  // bound, reached by a huge speed or gravity): the refusal ends the run
  // through StepFailure. The counters feed the report's broad-phase figure.
  auto stats = m_world.Step(m_timeStep);
  if (!stats) {
    m_failure = stats.GetError().message;
    return;
  }
  m_failure.clear();
  m_lastStep = stats.Value();
}

// The write-up's figure 2 funnel, in order: bodies, pairs the broad phase's
// structure met, pairs whose bounding spheres touch, SAT queries, touching
// pairs, contact points. Touching pairs and points include the manifolds
// reused without a SAT query (the write-up variant reuses none). Then which
// structure ran this step (StepStatistics' kindUsed), one counter per
// structure, 1 for the one that ran and 0 for the others: the names carry
// the structure (harness::kStructureCounterPrefix), so the counters stay
// the same list every step and the report shows them as a label.
std::vector<harness::StepCounter> TalusBackend::StepCounters() const {
  const StepStatistics& s = m_lastStep;
  std::vector<harness::StepCounter> counters = {
      {"bodies", static_cast<double>(s.bodies)},
      {"candidate pairs", static_cast<double>(s.broadPhase.candidatePairs)},
      {"sphere pairs", static_cast<double>(s.broadPhase.spherePairs)},
      {"SAT tests", static_cast<double>(s.narrowPhase.satTests)},
      {"intersecting pairs", static_cast<double>(s.narrowPhase.pairsTouching) + s.manifoldsReused},
      {"contact points", static_cast<double>(s.narrowPhase.manifoldPoints) + s.reusedContactPoints},
  };
  for (const BroadPhaseKind kind :
       {BroadPhaseKind::UniformGrid, BroadPhaseKind::AabbTree, BroadPhaseKind::BruteForce}) {
    counters.push_back({std::string(harness::kStructureCounterPrefix) + BroadPhaseName(kind),
                        s.broadPhase.kindUsed == kind ? 1.0 : 0.0});
  }
  return counters;
}

// World::Step's stages (StepStatistics::seconds), named and ordered as the
// engine's stage table (kStages, talus/step_stage.h) is.
std::vector<harness::StageTiming> TalusBackend::StageTimings() const {
  std::vector<harness::StageTiming> timings;
  timings.reserve(kStages.size());
  for (const StageInfo& stage : kStages)
    timings.push_back({std::string(stage.name), m_lastStep.seconds[stage.stage]});
  return timings;
}

void TalusBackend::TimeStages() {
  WorldSettings settings = m_world.Settings();
  settings.timeStages = true;
  [[maybe_unused]] const Status set = m_world.SetSettings(settings);
  assert(set);  // the world's own settings, one flag changed
}

harness::BodyReading TalusBackend::GetBodyState(int index) const {
  const auto state = m_world.GetBodyState(m_bodies.at(static_cast<std::size_t>(index)));
  assert(state);
  const talus::BodyState& body = state.Value();
  harness::BodyReading out;
  out.centerOfMass = body.centerOfMass;
  out.origin = body.position;
  out.orientation = body.orientation;
  out.linearVelocity = body.linearVelocity;
  out.angularVelocity = body.angularVelocity;
  out.mass = body.mass;
  const Mat3 rotation = body.orientation.toRotationMatrix();
  out.worldInertia = rotation * body.localInertia * rotation.transpose();
  return out;
}

std::vector<harness::ContactReading> TalusBackend::GetContacts() const {
  std::vector<harness::ContactReading> contacts;
  for (const ContactPointInfo& point : m_world.GetContactPoints()) {
    const int bodyA = m_scenarioIndexOfSlot.at(static_cast<std::size_t>(point.bodyA.index));
    const int bodyB = m_scenarioIndexOfSlot.at(static_cast<std::size_t>(point.bodyB.index));
    contacts.push_back({bodyA, bodyB, point.position, point.normal, point.depth});
  }
  return contacts;
}

const char* OnOff(bool on) { return on ? "on" : "off"; }

void TalusBackend::AddSettings(const Run& run, const WorldSettings& base) {
  const WorldSettings& s = m_world.Settings();
  const NarrowPhaseSettings& n = s.methods.narrowPhase;
  const NarrowPhaseSettings& bn = base.methods.narrowPhase;
  const std::string broadPhase =
      s.methods.forceBroadPhase
          ? std::string(BroadPhaseName(s.broadPhase)) +
                ", forced in every world (scenario world.broadPhase \"" +
                harness::BroadPhaseChoiceName(run.scenario.world.broadPhase) + "\")"
          : std::string(BroadPhaseName(s.broadPhase)) + "; brute force in worlds of at most " +
                std::to_string(kTinyWorldBodies) + " bodies (engine default)";
  m_settings = {
      {"engine", "Talus (double)"},
      {"variant", VariantName(m_variant)},
      {"time step (s)", SettingNumber(run.timeStep)},
      {"stepping", "World::Step(h), one step per Step()"},
      Choice("integrator", TranslationText(s.methods.translation), TranslationText(base.methods.translation),
             "the write-up's symplectic Euler: free flight lags the parabola by g h t / 2 (docs/dynamics.md, "
             "\"Translation exact for constant gravity\")"),
      Choice(
          "solver", SolverText(s), SolverText(base),
          s.methods.stepSolver == StepSolver::SoftStep
              ? "the soft step: soft contact springs over sub-steps instead of sweeps with Baumgarte's push "
                "(docs/dynamics.md, \"The soft step\")"
              : "the coloured order, whose colours split across threads with bit-identical results: the "
                "same rows in another order, so results differ from the pair order by the order "
                "(docs/dynamics.md, \"The coloured wide solver\")"),
      {"velocity iterations",
       std::to_string(s.velocityIterations) + (run.iterations > 0 ? "" : " (engine default)")},
      Choice("warm starting", OnOff(s.methods.warmStarting), OnOff(base.methods.warmStarting),
             "the write-up's: every step's solve starts from zero impulses, so a stack carries its load only "
             "after many sweeps"),
      Choice("block solver (a pair's normal rows together)", OnOff(s.methods.blockSolver),
             OnOff(base.methods.blockSolver),
             "the write-up's row by row: the first corner solved takes more load, and a 10-box column sways "
             "7.9 cm where the defaults hold it to 1e-14 m (docs/dynamics.md, \"Measured\")"),
      Choice(
          "friction solve", FrictionSolveText(s.methods.frictionSolve),
          FrictionSolveText(base.methods.frictionSolve),
          "the per-point rows (the write-up's; the only ones the coloured solver and the row-by-row "
          "normals have): a stopping box keeps about 0.6 of its slip a sweep instead of stopping in one "
          "(box_slide at 1/30 s, 5 sweeps: 2.6e-5 m short and rocking; docs/dynamics.md, \"Coupled block\")"),
      Choice("shock propagation", OnOff(s.methods.shockPropagation), OnOff(base.methods.shockPropagation),
             "the sweeps alone: a load on supports of a tenth of its mass or less is carried only after "
             "many steps, and meanwhile drives them into the ground and is thrown back (a 1000 kg slab on "
             "two 1 kg boxes drifts 0.7 m; docs/dynamics.md, \"Shock propagation\")"),
      Choice("extra velocity sweeps for new contacts", ExtraSweepsText(s), ExtraSweepsText(base),
             "the write-up's fixed sweep count: a new stack's first solve is left unconverged (a cold 10-box "
             "column needs about 150 sweeps not to sag by 1 mm; docs/dynamics.md, \"Constraints\")"),
      Choice(
          "position correction", PositionCorrectionName(s.methods.positionCorrection),
          PositionCorrectionName(base.methods.positionCorrection),
          "Bullet's split impulses: the push-out moves positions only, so it adds no kinetic energy (a box "
          "started 5 cm deep leaves at < 1e-3 m/s instead of > 0.3 m/s; docs/dynamics.md, \"Constraints\")"),
      {"position iterations", s.methods.positionCorrection == PositionCorrection::Baumgarte
                                  ? "unused"
                                  : std::to_string(s.positionIterations)},
      {"baumgarte factor", SettingNumber(s.baumgarte)},
      {"slop (m)", SettingNumber(s.slop)},
      {"restitution threshold (m/s)", SettingNumber(s.restitutionThreshold)},
      Choice("bounce timing", BounceTimingText(s.methods.bounceTiming),
             BounceTimingText(base.methods.bounceTiming),
             "the write-up's: the impact is taken at the step's boundary, so a 1 m drop at 60 Hz lands up to "
             "a step early or late and its apex errs by up to (1 + e^2) v h (docs/dynamics.md, \"Bounces "
             "timed inside the step\")"),
      {"friction combine", harness::CombineRuleName(run.scenario.world.frictionCombine)},
      {"restitution combine", harness::CombineRuleName(run.scenario.world.restitutionCombine)},
      {"broad phase", broadPhase},
      Choice("SAT", SatText(n.satMode), SatText(bn.satMode),
             "the write-up's search of all 2F + E^2 axes: the same contacts for more work "
             "(docs/collision-narrow-phase.md)"),
      Choice("SAT cache", OnOff(n.useSatCache), OnOff(bn.useSatCache),
             "the write-up describes the cache but did not build it: every pair searched from scratch"),
      Choice("manifold reuse (m of relative motion)", ReuseText(n.reuseDistance), ReuseText(bn.reuseDistance),
             "the write-up runs the narrow phase on every pair every step (docs/collision-narrow-phase.md)"),
      Choice("manifolds", ManifoldText(n.manifoldMode), ManifoldText(bn.manifoldMode),
             "the write-up's points: vertices near the contact plane with one depth for the whole manifold "
             "(docs/collision-narrow-phase.md)"),
      Choice("persistent points (m break distance)", PersistenceText(n), PersistenceText(bn),
             "the write-up keeps only the points of the step (docs/collision-narrow-phase.md)"),
      Choice(
          "speculative margin (m)", SpeculativeMarginText(s), SpeculativeMarginText(base),
          "the write-up's fixed margin: a corner that lands within the step sinks in and is pushed out (at "
          "1/30 s tall_box_tipping 15 degrees 4.4e-4 -> 0.18 tolerances, hull_rest 4e-14 -> 0.54; "
          "docs/testbed-sweeps.md)"),
      Choice("gyroscopic term", GyroscopicText(s.methods.rotation), GyroscopicText(base.methods.rotation),
             "the second-order splitting, the write-up's order of accuracy: L still kept, the energy error "
             "O((h w)^2), 36 times the fourth order's at 1/30 s on gazebo_boxes (docs/dynamics.md, "
             "\"Rotation\")"),
      {"damping", "none"},
      {"sleeping", OnOff(s.sleeping)},
      s.threads == 1 ? harness::Setting{"threads", "1"}
                     : harness::Setting{"threads", std::to_string(s.threads), "1",
                                        "the step's broad-phase proxies, narrow phase and integration "
                                        "spread over the threads; results bit-identical, wall time only"},
      {"hull shapes", "talus::BuildHull on the scenario points, in the body frame"},
      {"mass properties",
       "from talus::reference::ComputeBodyMass (exact), body frame, centre of mass at the centroid"},
  };
  // Listed only where the scenario uses them, so other runs' records stay as they were.
  if (!run.scenario.loads.empty() || !run.scenario.impulses.empty()) {
    m_settings.push_back({"loads and impulses",
                          "World::ApplyForce (at a point) or ApplyForceToCenter and ApplyTorque before each "
                          "step, scaled by the step's share of the window; World::ApplyLinearImpulse at the "
                          "impulse's step"});
  }
  if (std::any_of(run.scenario.bodies.begin(), run.scenario.bodies.end(),
                  [](const harness::BodySpec& b) { return b.motion == harness::Motion::Kinematic; })) {
    m_settings.push_back({"kinematic bodies",
                          "BodyType::Kinematic with the prescribed velocities: moved by them each step, "
                          "infinite mass to contacts"});
  }
}

}  // namespace

Result<WorldSettings> TalusRowSettings(const harness::Run& run, std::string_view row,
                                       const TalusBackendOptions& options) {
  for (const Variant variant :
       {Variant::Defaults, Variant::WriteUp, Variant::SplitImpulses, Variant::Coloured, Variant::Soft}) {
    if (row != VariantName(variant)) continue;
    auto configured = ConfigureRow(run, variant, options);
    if (!configured) return configured.GetError();
    return configured.Value().settings;
  }
  // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive)
  // on "..." + std::string(row) here.
  std::string message = "\"";
  message += row;
  message += "\" is not a Talus row (talus, talus-writeup, talus-split, talus-coloured, talus-soft)";
  return Error{message};
}

void RegisterTalusBackends(harness::BackendRegistry& registry, TalusBackendOptions options) {
  // A Talus World owns all its state; the engine has no globals.
  const harness::ThreadSafety independent = harness::ThreadSafety::Independent();
  registry.Register(
      "talus", "Talus (double): the engine's defaults, WorldSettings{}, with what the scenario states",
      independent,
      [options](const Run& run) { return TalusBackend::Create(run, Variant::Defaults, options); });
  registry.Register("talus-writeup",
                    "Talus (double): the write-up's choices (full SAT, write-up manifolds, row-by-row "
                    "solver, no warm starting)",
                    independent, [options](const Run& run) {
                      return TalusBackend::Create(run, Variant::WriteUp, options);
                    });
  registry.Register(
      "talus-split", "Talus (double): engine defaults plus split impulses", independent,
      [options](const Run& run) { return TalusBackend::Create(run, Variant::SplitImpulses, options); });
  registry.Register("talus-coloured",
                    "Talus (double): engine defaults with the coloured wide solver (four pairs per SIMD "
                    "bundle, colours splittable across threads) instead of the scalar pair order",
                    independent, [options](const Run& run) {
                      return TalusBackend::Create(run, Variant::Coloured, options);
                    });
  registry.Register("talus-soft",
                    "Talus (double): the soft step solver (4 sub-steps of soft contacts, relax, "
                    "restitution; Box2D v3's) instead of Sequential Impulses",
                    independent,
                    [options](const Run& run) { return TalusBackend::Create(run, Variant::Soft, options); });
}

}  // namespace talus::reference
