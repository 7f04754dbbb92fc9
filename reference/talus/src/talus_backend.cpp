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

#include <cassert>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "talus/body.h"
#include "talus/hull_builder.h"
#include "talus/reference/body_mass.h"
#include "talus/shape.h"
#include "talus/world.h"

namespace talus::reference {
namespace {

using harness::BodySpec;
using harness::CombineRule;
using harness::Run;

/// The testbed's convergence test of the extra sweeps for new contacts,
/// m/s (WorldSettings::velocityTolerance; the engine's default is 1e-3).
constexpr double kNewContactTolerance = 1e-9;

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
  void AddSettings(const Run& run);

  World m_world;
  Variant m_variant;
  double m_timeStep = 0.0;
  std::vector<BodyId> m_bodies;              // by scenario index
  std::vector<int> m_scenarioIndexOfSlot;    // world body index -> scenario index
  std::vector<BodyMass> m_masses;            // by scenario index
  std::vector<harness::Setting> m_settings;  // fixed at creation
  StepStatistics m_lastStep;                 // counters of the last Step (zero before the first)
  std::string m_failure;                     // World::Step's refusal of the last step; empty when it ran
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
    case PositionCorrection::NonlinearGaussSeidel:
      return "non-linear Gauss-Seidel";
  }
  return "unknown";
}

// The extra sweeps new contacts get, with the engine's default and the
// reason beside it when the variant converges them tighter.
harness::Setting ExtraSweepsSetting(const WorldSettings& s) {
  harness::Setting setting{"extra velocity sweeps for new contacts", "none"};
  if (s.maxVelocityIterations <= s.velocityIterations) return setting;
  setting.value = "up to " + std::to_string(s.maxVelocityIterations) + " sweeps, until changes < " +
                  SettingNumber(s.velocityTolerance) + " m/s";
  const double engineTolerance = WorldSettings{}.velocityTolerance;
  if (s.velocityTolerance != engineTolerance) {
    setting.engineDefault = "until changes < " + SettingNumber(engineTolerance) + " m/s";
    setting.effect =
        "new contacts start converged: the engine's 1e-3 m/s leaves a permanent offset of about 1e-3 h per "
        "contact (a 5e-5 rad tilt of tall_box_tipping, a 0.1 mm sag of box_column_5 at 1/30 s); extra "
        "sweeps only in steps with new pairs";
  }
  return setting;
}

// How friction is solved, with the engine's default and the effect beside
// it when the variant differs.
harness::Setting FrictionSolveSetting(const WorldSettings& s) {
  if (s.frictionSolve == FrictionSolve::PerPoint) {
    return {"friction solve", "per point (two rows a point, one after another)"};
  }
  return {"friction solve",
          "joint block: a sticking pair's normals and friction (slip and spin patterns) solved together, "
          "else per point",
          "per point",
          "a stopping or sticking box is at rest within a sweep instead of converging by about 0.6 a sweep "
          "(box_slide at 1/30 s, 5 sweeps: 2.6e-5 m short and rocking before, exact after); contact scenes "
          "0.8-0.9 times the cost (the accepted pair's friction rows are skipped)"};
}

// The speculative margin, and whether it grows with the step's motion.
harness::Setting SpeculativeMarginSetting(const WorldSettings& s) {
  const std::string fixed = SettingNumber(s.narrowPhase.speculativeMargin);
  if (!s.speculativeMotion) return {"speculative margin (m)", fixed};
  return {"speculative margin (m)",
          fixed + ", or the pair's reach this step where larger (h (|v| + |w| rho + g h) of each body)",
          fixed + " (fixed)",
          "a body that can reach the other shape within the step is in the manifold before it lands: "
          "at 1/30 s tall_box_tipping 15 degrees 0.18 -> 4.4e-4 tolerances, 24 degrees 0.034 -> 0.008, "
          "hull_rest 0.54 -> 4e-14; box_toss at 1/120 to 1/30 s moves within its round-off spread; no "
          "change where the reach is below the margin"};
}

WorldSettings MakeSettings(const Run& run, Variant variant, FrictionCombine friction,
                           RestitutionCombine restitution, const TalusBackendOptions& options) {
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
  // The scenario's gyroscopic term, in the engine's momentum-conserving
  // form (free rigid body splitting; fourth order but for talus-writeup,
  // which keeps the second-order Strang step: measured 35 times smaller
  // energy errors at equal step on gazebo_boxes, docs/dynamics.md); without
  // it the write-up's constant rate.
  settings.rotation = !run.scenario.world.gyroscopic ? RotationIntegrator::ConstantRate
                      : variant == Variant::WriteUp  ? RotationIntegrator::MomentumSplitting
                                                     : RotationIntegrator::MomentumSplittingFourthOrder;
  // The scenario's broad phase: auto keeps the engine's default (the grid,
  // brute force in tiny worlds); any other choice runs in every world.
  switch (run.scenario.world.broadPhase) {
    case harness::BroadPhaseChoice::Auto:
      break;
    case harness::BroadPhaseChoice::UniformGrid:
      settings.broadPhase = BroadPhaseKind::UniformGrid;
      settings.forceBroadPhase = true;
      break;
    case harness::BroadPhaseChoice::AabbTree:
      settings.broadPhase = BroadPhaseKind::AabbTree;
      settings.forceBroadPhase = true;
      break;
    case harness::BroadPhaseChoice::BruteForce:
      settings.broadPhase = BroadPhaseKind::BruteForce;
      settings.forceBroadPhase = true;
      break;
  }
  // The scenario's bounce timing: auto keeps the variant's own (below).
  switch (run.scenario.world.bounceTiming) {
    case harness::BounceTimingChoice::Auto:
      // The write-up bounces at the step's boundary; the others take the
      // engine's default.
      if (variant == Variant::WriteUp) settings.bounceTiming = BounceTiming::StepBoundary;
      break;
    case harness::BounceTimingChoice::TimeOfImpact:
      settings.bounceTiming = BounceTiming::TimeOfImpact;
      break;
    case harness::BounceTimingChoice::StepBoundary:
      settings.bounceTiming = BounceTiming::StepBoundary;
      break;
  }
  // Free flight exact for constant gravity (the write-up's symplectic Euler
  // for talus-writeup): with bounces timed inside the step it was measured
  // better or equal on every truth of the suite (docs/dynamics.md).
  settings.translation = TranslationIntegrator::ExactConstantAcceleration;
  // New contacts (no impulses to warm start from) converged to 1e-9 m/s
  // instead of the engine's 1e-3 (same cap of extra sweeps): the residual
  // velocity of that first solve is never corrected afterwards (the rest
  // sits inside the slop), so 1e-3 m/s left a permanent offset of about
  // 1e-3 h per contact: a 5e-5 rad tilt of tall_box_tipping at 1/30 s, a
  // 1e-4 m sag of box_column_5, against ODE's direct solver's 1e-9
  // (docs/testbed-sweeps.md). The extra sweeps run only in steps with new
  // pairs.
  settings.velocityTolerance = kNewContactTolerance;
  if (variant == Variant::WriteUp) {
    settings.velocityTolerance = WorldSettings{}.velocityTolerance;
    settings.translation = TranslationIntegrator::SymplecticEuler;
    settings.narrowPhase.satMode = SatMode::Full;
    settings.narrowPhase.manifoldMode = ManifoldMode::WriteUp;
    settings.narrowPhase.useSatCache = false;
    settings.narrowPhase.reuseDistance = 0.0;  // the write-up runs the narrow phase every step
    settings.narrowPhase.persistence = ManifoldPersistence::Fresh;  // and keeps only its points
    settings.warmStarting = false;
    // The write-up's solver: plain row-by-row Gauss-Seidel, a fixed number
    // of sweeps (a cap below the iteration count means no extra sweeps).
    settings.blockSolver = false;
    settings.maxVelocityIterations = 1;
    settings.positionCorrection = PositionCorrection::Baumgarte;
    settings.contactSolver = ContactSolverKind::SequentialImpulses;  // the write-up's scalar order
  } else if (variant == Variant::Coloured) {
    settings.contactSolver = ContactSolverKind::ColouredWide;
  } else if (variant == Variant::SplitImpulses) {
    settings.positionCorrection = PositionCorrection::SplitImpulses;
  } else if (variant == Variant::Soft) {
    // The soft step (docs/dynamics.md, "The soft step") at the engine's
    // 4 sub-steps: the run's iterations are a sweep count, which this solver
    // does not have (it solves once and relaxes once per sub-step), so they
    // leave it alone, as every sweep setting above.
    settings.stepSolver = StepSolver::SoftStep;
  }
  // A sticking pair's normals and friction solved as one block (the scalar
  // variants; the coloured solver has none): measured on the sweep
  // (docs/dynamics.md), a box stopping at 30 Hz with 5 sweeps comes to rest
  // at the exact distance instead of 2.6e-5 m short and rocking, and the
  // contact scenes cost 0.8-0.9 times as much (the pair's friction rows are
  // skipped when the block is accepted).
  // A speculative margin as large as the step's reach (the same variants):
  // measured on the sweep, a box tipping over at 1/30 s or a hull landing
  // on a corner is caught at the surface instead of sinking in and being
  // pushed out (at 1/30 s tall_box_tipping 15 degrees 0.18 -> 4.4e-4
  // tolerances, 24 degrees 0.034 -> 0.008, hull_rest 0.54 -> 4e-14), and
  // nothing changes where the reach is below the fixed margin (fine steps,
  // slow bodies: the same bits).
  if (variant == Variant::Defaults || variant == Variant::SplitImpulses || variant == Variant::Soft) {
    settings.speculativeMotion = true;
    // The soft step has no joint block (its friction rows are per point).
    if (variant != Variant::Soft) settings.frictionSolve = FrictionSolve::JointBlock;
  }
  return settings;
}

Result<std::unique_ptr<harness::Backend>> TalusBackend::Create(const Run& run, Variant variant,
                                                               const TalusBackendOptions& options) {
  const std::string prefix = std::string(VariantName(variant)) + ": ";
  auto friction = ToFrictionCombine(run.scenario.world.frictionCombine);
  if (!friction) return Error{prefix + friction.GetError().message};
  auto restitution = ToRestitutionCombine(run.scenario.world.restitutionCombine);
  if (!restitution) return Error{prefix + restitution.GetError().message};
  auto world = World::Create(MakeSettings(run, variant, friction.Value(), restitution.Value(), options));
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
    def.type = spec.motion == harness::Motion::Dynamic ? BodyType::Dynamic : BodyType::Static;
    def.position = spec.position;
    def.orientation = spec.orientation;
    def.shape = std::move(shape).Value();
    def.friction = spec.friction;
    def.restitution = spec.restitution;
    def.allowSleep = false;
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
  backend->AddSettings(run);
  return std::unique_ptr<harness::Backend>(std::move(backend));
}

void TalusBackend::Step() {
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

// World::Step's stages (StepStatistics::seconds), named as the stage
// functions of world_step.cpp are, in the order they run.
std::vector<harness::StageTiming> TalusBackend::StageTimings() const {
  const StageTimes& t = m_lastStep.seconds;
  return {{"UpdateBroadPhase", t.updateBroadPhase},
          {"IntegrateVelocities", t.integrateVelocities},
          {"FindContacts", t.findContacts},
          {"PrepareContacts", t.prepareContacts},
          {"SolveVelocities", t.solveVelocities},
          {"SolveSplitImpulses", t.solveSplitImpulses},
          {"ScatterAndStoreImpulses", t.scatterAndStoreImpulses},
          {"IntegratePositions", t.integratePositions},
          {"CorrectPositions", t.correctPositions},
          {"UpdateSleep", t.sleep}};
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

void TalusBackend::AddSettings(const Run& run) {
  const WorldSettings& s = m_world.Settings();
  const char* sat = s.narrowPhase.satMode == SatMode::Full ? "full (every face and edge pair)"
                                                           : "Gauss-map pruned edge pairs";
  const char* manifold = s.narrowPhase.manifoldMode == ManifoldMode::WriteUp
                             ? "write-up (vertices near the contact plane, one depth)"
                             : "clipped incident face, reduced to 4 points";
  const std::string broadPhase =
      s.forceBroadPhase ? std::string(BroadPhaseName(s.broadPhase)) +
                              ", forced in every world (scenario world.broadPhase \"" +
                              harness::BroadPhaseChoiceName(run.scenario.world.broadPhase) + "\")"
                        : std::string(BroadPhaseName(s.broadPhase)) + "; brute force in worlds of at most " +
                              std::to_string(kTinyWorldBodies) + " bodies (engine default)";
  m_settings = {
      {"engine", "Talus (double)"},
      {"variant", VariantName(m_variant)},
      {"time step (s)", SettingNumber(run.timeStep)},
      {"stepping", "World::Step(h), one step per Step()"},
      {"integrator", s.translation == TranslationIntegrator::SymplecticEuler
                         ? "symplectic Euler (v += h a; x += h v)"
                         : "v += h a; x += h (v0 + v) / 2 for a body no impulse touched (exact for constant "
                           "acceleration), else x += h v"},
      {"solver", s.stepSolver == StepSolver::SoftStep
                     ? "soft step: " + std::to_string(s.softStep.substeps) + " sub-steps, contacts at " +
                           SettingNumber(s.softStep.contactHertz) +
                           " Hz (at most a quarter of the sub-step "
                           "rate), damping ratio " +
                           SettingNumber(s.softStep.dampingRatio) + ", push-out " +
                           SettingNumber(s.softStep.pushOutSpeed) +
                           " m/s; the sweep settings below are unused"
                 : s.contactSolver == ContactSolverKind::SequentialImpulses
                     ? "sequential impulses (scalar, pair order)"
                     : "sequential impulses, coloured, four pairs per SIMD bundle"},
      {"velocity iterations",
       std::to_string(s.velocityIterations) + (run.iterations > 0 ? "" : " (engine default)")},
      {"warm starting", OnOff(s.warmStarting)},
      {"block solver (a pair's normal rows together)", OnOff(s.blockSolver)},
      FrictionSolveSetting(s),
      ExtraSweepsSetting(s),
      {"position correction", PositionCorrectionName(s.positionCorrection)},
      {"position iterations", s.positionCorrection == PositionCorrection::Baumgarte
                                  ? "unused"
                                  : std::to_string(s.positionIterations)},
      {"baumgarte factor", SettingNumber(s.baumgarte)},
      {"slop (m)", SettingNumber(s.slop)},
      {"restitution threshold (m/s)", SettingNumber(s.restitutionThreshold)},
      {"bounce timing", s.bounceTiming == BounceTiming::TimeOfImpact
                            ? "time of impact inside the step (reflected flight to the step's end)"
                            : "step boundary (the write-up's)"},
      {"friction combine", harness::CombineRuleName(run.scenario.world.frictionCombine)},
      {"restitution combine", harness::CombineRuleName(run.scenario.world.restitutionCombine)},
      {"broad phase", broadPhase},
      {"SAT", sat},
      {"SAT cache", OnOff(s.narrowPhase.useSatCache)},
      {"manifold reuse (m of relative motion)",
       s.narrowPhase.reuseDistance > 0.0 ? SettingNumber(s.narrowPhase.reuseDistance) : "off"},
      {"manifolds", manifold},
      {"persistent points (m break distance)", s.narrowPhase.persistence == ManifoldPersistence::Accumulate
                                                   ? SettingNumber(s.narrowPhase.persistenceDistance)
                                                   : "off"},
      SpeculativeMarginSetting(s),
      {"gyroscopic term", s.rotation == RotationIntegrator::ConstantRate
                              ? "off (WorldSettings::rotation = ConstantRate)"
                          : s.rotation == RotationIntegrator::MomentumSplitting
                              ? "on (WorldSettings::rotation = MomentumSplitting: L kept, exact "
                                "rotations about the principal axes)"
                          : s.rotation == RotationIntegrator::MomentumSplittingFourthOrder
                              ? "on (WorldSettings::rotation = MomentumSplittingFourthOrder: L kept, exact "
                                "rotations about the principal axes, fourth order)"
                              : "on (WorldSettings::rotation = ImplicitGyroscopic)"},
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
}

}  // namespace

void RegisterTalusBackends(harness::BackendRegistry& registry, TalusBackendOptions options) {
  // A Talus World owns all its state; the engine has no globals.
  const harness::ThreadSafety independent = harness::ThreadSafety::Independent();
  registry.Register(
      "talus", "Talus (double): engine defaults (pruned SAT, clipped manifolds, warm starting)", independent,
      [options](const Run& run) { return TalusBackend::Create(run, Variant::Defaults, options); });
  registry.Register(
      "talus-writeup",
      "Talus (double): the write-up's choices (full SAT, write-up manifolds, no warm starting)", independent,
      [options](const Run& run) { return TalusBackend::Create(run, Variant::WriteUp, options); });
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
