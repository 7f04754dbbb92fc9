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
//
// Which settings each row runs with is talus_variants.cpp's; the settings
// list it records, talus_settings_text.cpp's; the names of the engine's
// enum values, talus_enum_names.cpp's. This file is the backend itself and
// its registration.
#include "talus/reference/talus_backend.h"

#include <cassert>
#include <memory>
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
#include "talus_enum_names.h"
#include "talus_settings_text.h"
#include "talus_variants.h"

namespace talus::reference {
namespace {

using harness::BodySpec;
using harness::Run;

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
  backend->m_settings = TalusSettingsText(run, VariantName(variant), backend->m_world.Settings(), base);
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
// engine's stage table (kStages, talus/step_stage.h) is; only the stages
// the world's step solver ran (StageTimes::ran), so the soft step reports
// no empty integration rows.
std::vector<harness::StageTiming> TalusBackend::StageTimings() const {
  std::vector<harness::StageTiming> timings;
  timings.reserve(kStages.size());
  for (const StageInfo& stage : kStages) {
    if (!m_lastStep.seconds.ran[static_cast<std::size_t>(stage.stage)]) continue;
    timings.push_back({std::string(stage.name), m_lastStep.seconds[stage.stage]});
  }
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

}  // namespace

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
  registry.Register("talus-manifold",
                    "Talus (double): engine defaults with friction per manifold (slip at the centre "
                    "and a spin row) instead of the coupled block and per-point rows",
                    independent, [options](const Run& run) {
                      return TalusBackend::Create(run, Variant::ManifoldFriction, options);
                    });
  registry.Register("talus-coupled",
                    "Talus (double): engine defaults with the coupled block on every face pair (the "
                    "default before adaptive friction) instead of manifold rows on the lightly loaded ones",
                    independent, [options](const Run& run) {
                      return TalusBackend::Create(run, Variant::CoupledFriction, options);
                    });
}

}  // namespace talus::reference
