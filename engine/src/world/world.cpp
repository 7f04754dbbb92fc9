// The World's boundary: settings, body creation and destruction, state
// access. Everything the user hands in is validated here, completely, before
// anything is written, so a refused call leaves the world untouched. The
// step itself is in world/world_step.cpp.
#include "talus/world.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <system_error>

#include "dynamics/integrator.h"
#include "jobs/job_pool.h"
#include "world/world_data.h"

namespace talus {
namespace {

bool Finite(const Vec3& v) { return v.allFinite(); }

std::string Describe(const Vec3& v) {
  std::string text = "(";
  text += std::to_string(v.x());
  text += ", ";
  text += std::to_string(v.y());
  text += ", ";
  text += std::to_string(v.z());
  text += ")";
  return text;
}

std::string CheckRange(const char* name, double value, double lo, double hi) {
  if (std::isfinite(value) && value >= lo && value <= hi) return {};
  return std::string("WorldSettings.") + name + " = " + std::to_string(value) + " is outside [" +
         std::to_string(lo) + ", " + std::to_string(hi) + "]";
}

std::string CheckBodyDef(const BodyDef& def) {
  if (!Finite(def.position)) return "BodyDef.position " + Describe(def.position) + " is not finite";
  if (!def.orientation.coeffs().allFinite() || def.orientation.norm() < 1e-12) {
    return "BodyDef.orientation is not a finite non-zero quaternion";
  }
  if (!Finite(def.linearVelocity))
    return "BodyDef.linearVelocity " + Describe(def.linearVelocity) + " is not finite";
  if (!Finite(def.angularVelocity)) {
    return "BodyDef.angularVelocity " + Describe(def.angularVelocity) + " is not finite";
  }
  if (!Finite(def.localCenterOfMass)) return "BodyDef.localCenterOfMass is not finite";
  if (!std::isfinite(def.density) || def.density < 0.0) {
    return "BodyDef.density = " + std::to_string(def.density) + " kg/m^3 must be finite and >= 0";
  }
  if (!std::isfinite(def.friction) || def.friction < 0.0) {
    return "BodyDef.friction = " + std::to_string(def.friction) + " must be finite and >= 0";
  }
  if (!std::isfinite(def.restitution) || def.restitution < 0.0 || def.restitution > 1.0) {
    return "BodyDef.restitution = " + std::to_string(def.restitution) + " must be in [0, 1]";
  }
  if (def.type != BodyType::Dynamic) return {};
  if (def.shape && def.density > 0.0) return {};
  if (!std::isfinite(def.mass) || def.mass <= 0.0) {
    return "BodyDef.mass = " + std::to_string(def.mass) + " kg must be finite and > 0 for a dynamic body";
  }
  const Mat3& inertia = def.localInertia;
  if (!inertia.allFinite()) return "BodyDef.localInertia is not finite";
  if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > 1e-9 * inertia.cwiseAbs().maxCoeff()) {
    return "BodyDef.localInertia is not symmetric";
  }
  const Eigen::LLT<Mat3> llt(inertia);
  if (llt.info() != Eigen::Success || inertia.diagonal().minCoeff() <= 0.0) {
    return "BodyDef.localInertia is not positive definite";
  }
  return {};
}

Status Refuse(std::string message) { return Error{std::move(message)}; }

// A job pool of `threads` threads, or an Error when the system refuses to
// start one (too many threads for the process); nothing is left running.
Result<std::unique_ptr<JobPool>> StartThreads(int threads) {
  try {
    return std::make_unique<JobPool>(threads);
  } catch (const std::system_error& error) {
    return Error{"WorldSettings.threads = " + std::to_string(threads) +
                 ": the system refused to start a thread (" + error.what() + ")"};
  }
}

// Wakes a dynamic body and resets its rest timer, which wakes its island at
// the next sleep pass.
void WakeBody(WorldData& d, std::size_t i) {
  if (d.sims[i].type != BodyType::Dynamic) return;
  d.sims[i].awake = true;
  d.sleep[i].restTime = 0.0;
}

}  // namespace

namespace {

// An enum field holding a value outside its enum (a cast integer, memory
// garbage): names the field and its type.
template <typename Enum>
std::string NotAnEnum(const char* field, Enum value, const char* type) {
  return std::string("WorldSettings.methods.") + field + " = " + std::to_string(static_cast<int>(value)) +
         " is not a " + type;
}

std::string CheckMethodEnums(const MethodSettings& m) {
  if (m.positionCorrection != PositionCorrection::Baumgarte &&
      m.positionCorrection != PositionCorrection::SplitImpulses) {
    return NotAnEnum("positionCorrection", m.positionCorrection, "PositionCorrection");
  }
  if (m.rotation != RotationIntegrator::ConstantRate && m.rotation != RotationIntegrator::MomentumSplitting &&
      m.rotation != RotationIntegrator::MomentumSplittingFourthOrder) {
    return NotAnEnum("rotation", m.rotation, "RotationIntegrator");
  }
  if (m.contactOrder != ContactOrder::PairByPair && m.contactOrder != ContactOrder::ByColour) {
    return NotAnEnum("contactOrder", m.contactOrder, "ContactOrder");
  }
  if (m.frictionSolve != FrictionSolve::PerPoint && m.frictionSolve != FrictionSolve::CoupledBlock &&
      m.frictionSolve != FrictionSolve::PerManifold && m.frictionSolve != FrictionSolve::Adaptive) {
    return NotAnEnum("frictionSolve", m.frictionSolve, "FrictionSolve");
  }
  if (m.translation != TranslationIntegrator::SymplecticEuler &&
      m.translation != TranslationIntegrator::ExactConstantAcceleration) {
    return NotAnEnum("translation", m.translation, "TranslationIntegrator");
  }
  if (m.bounceTiming != BounceTiming::StepBoundary && m.bounceTiming != BounceTiming::TimeOfImpact) {
    return NotAnEnum("bounceTiming", m.bounceTiming, "BounceTiming");
  }
  if (m.narrowPhase.persistence != ManifoldPersistence::Fresh &&
      m.narrowPhase.persistence != ManifoldPersistence::Accumulate) {
    return NotAnEnum("narrowPhase.persistence", m.narrowPhase.persistence, "ManifoldPersistence");
  }
  return {};
}

// Combinations in which a switch would do nothing are refused rather than
// silently run as something else.
std::string CheckMethodCombinations(const MethodSettings& m) {
  // The coupled block is a pair's normal block with its friction: without
  // either it would silently be the per-point rows.
  if (m.frictionSolve == FrictionSolve::CoupledBlock && m.contactOrder != ContactOrder::PairByPair) {
    return "WorldSettings.methods.frictionSolve = CoupledBlock needs contactOrder = "
           "PairByPair: the coloured order has no coupled block; select frictionSolve = PerPoint with it";
  }
  if (m.frictionSolve == FrictionSolve::CoupledBlock && !m.blockSolver) {
    return "WorldSettings.methods.frictionSolve = CoupledBlock needs blockSolver = true: the "
           "coupled block extends a pair's normal block, which blockSolver = false turns off; select "
           "frictionSolve = PerPoint with it";
  }
  if (m.frictionSolve == FrictionSolve::Adaptive && m.contactOrder != ContactOrder::PairByPair) {
    return "WorldSettings.methods.frictionSolve = Adaptive needs contactOrder = PairByPair: the coloured "
           "order has neither the coupled block nor the manifold's rows; select frictionSolve = PerPoint "
           "with it";
  }
  if (m.frictionSolve == FrictionSolve::Adaptive && !m.blockSolver) {
    return "WorldSettings.methods.frictionSolve = Adaptive needs blockSolver = true: its loaded pairs take "
           "the "
           "coupled block, which extends a pair's normal block; select frictionSolve = PerPoint or "
           "PerManifold "
           "with it";
  }
  if (m.frictionSolve == FrictionSolve::PerManifold && m.contactOrder != ContactOrder::PairByPair) {
    return "WorldSettings.methods.frictionSolve = PerManifold needs contactOrder = PairByPair: the coloured "
           "order's lanes hold per-point friction rows; select frictionSolve = PerPoint with it";
  }
  return {};
}

std::string CheckMethodRanges(const MethodSettings& m) {
  if (m.maxVelocityIterations < 1 || m.maxVelocityIterations > 1000) {
    return "WorldSettings.methods.maxVelocityIterations = " + std::to_string(m.maxVelocityIterations) +
           " is outside [1, 1000]";
  }
  if (!std::isfinite(m.velocityTolerance) || m.velocityTolerance < 0.0) {
    return "WorldSettings.methods.velocityTolerance = " + std::to_string(m.velocityTolerance) +
           " m/s must be finite and >= 0";
  }
  const NarrowPhaseSettings& n = m.narrowPhase;
  if (!std::isfinite(n.speculativeMargin) || n.speculativeMargin < 0.0) {
    return "WorldSettings.methods.narrowPhase.speculativeMargin = " + std::to_string(n.speculativeMargin) +
           " m must be finite and >= 0";
  }
  if (!std::isfinite(n.reuseDistance) || n.reuseDistance < 0.0) {
    return "WorldSettings.methods.narrowPhase.reuseDistance = " + std::to_string(n.reuseDistance) +
           " m must be finite and >= 0 (0 turns manifold reuse off)";
  }
  if (!std::isfinite(n.persistenceDistance) || !(n.persistenceDistance > 0.0)) {
    return "WorldSettings.methods.narrowPhase.persistenceDistance = " +
           std::to_string(n.persistenceDistance) + " m must be finite and > 0";
  }
  return {};
}

std::string CheckUserChoices(const WorldSettings& s) {
  if (!Finite(s.gravity)) return "WorldSettings.gravity " + Describe(s.gravity) + " is not finite";
  if (s.velocityIterations < 1 || s.velocityIterations > 1000) {
    return "WorldSettings.velocityIterations = " + std::to_string(s.velocityIterations) +
           " is outside [1, 1000]";
  }
  if (s.positionIterations < 1 || s.positionIterations > 1000) {
    return "WorldSettings.positionIterations = " + std::to_string(s.positionIterations) +
           " is outside [1, 1000]";
  }
  if (s.broadPhase != BroadPhaseKind::UniformGrid && s.broadPhase != BroadPhaseKind::AabbTree &&
      s.broadPhase != BroadPhaseKind::BruteForce) {
    return "WorldSettings.broadPhase = " + std::to_string(static_cast<int>(s.broadPhase)) +
           " is not a BroadPhaseKind";
  }
  if (s.threads < 1 || s.threads > kMaxThreads) {
    return "WorldSettings.threads = " + std::to_string(s.threads) + " is outside [1, " +
           std::to_string(kMaxThreads) + "]";
  }
  constexpr double kHuge = 1e300;
  for (const std::string& error :
       {CheckRange("baumgarte", s.baumgarte, 0.0, 1.0), CheckRange("slop", s.slop, 0.0, 1.0),
        CheckRange("restitutionThreshold", s.restitutionThreshold, 0.0, kHuge),
        CheckRange("sleepLinearVelocity", s.sleepLinearVelocity, 0.0, kHuge),
        CheckRange("sleepAngularVelocity", s.sleepAngularVelocity, 0.0, kHuge),
        CheckRange("timeToSleep", s.timeToSleep, 0.0, kHuge)}) {
    if (!error.empty()) return error;
  }
  return {};
}

}  // namespace

std::string ValidateSettings(const WorldSettings& s) {
  for (std::string error : {CheckUserChoices(s), CheckMethodEnums(s.methods), CheckMethodRanges(s.methods),
                            CheckMethodCombinations(s.methods), ValidateSoftStepSettings(s)}) {
    if (!error.empty()) return error;
  }
  return {};
}

World::World() : m_data(std::make_unique<WorldData>()) {}
World::World(std::unique_ptr<WorldData> data) : m_data(std::move(data)) {}
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;
World::~World() = default;

Result<World> World::Create(const WorldSettings& settings) {
  if (std::string error = ValidateSettings(settings); !error.empty()) return Error{error};
  auto data = std::make_unique<WorldData>();
  if (settings.threads != data->jobs->ThreadCount()) {
    auto jobs = StartThreads(settings.threads);
    if (!jobs) return jobs.GetError();
    data->jobs = std::move(jobs).Value();
  }
  data->settings = settings;
  return World(std::move(data));
}

const WorldSettings& World::Settings() const { return m_data->settings; }

Status World::SetSettings(const WorldSettings& settings) {
  if (std::string error = ValidateSettings(settings); !error.empty()) return Refuse(error);
  // A new thread count starts its threads before anything changes, so a
  // refusal leaves the world as it was.
  if (settings.threads != m_data->jobs->ThreadCount()) {
    auto jobs = StartThreads(settings.threads);
    if (!jobs) return jobs.GetError();
    m_data->jobs = std::move(jobs).Value();
  }
  m_data->settings = settings;
  // Turning sleeping off wakes everything that sleeps.
  if (!settings.sleeping) {
    for (std::size_t i = 0; i < m_data->sims.size(); ++i) {
      m_data->sims[i].awake = true;
      m_data->sleep[i].restTime = 0.0;
    }
  }
  return std::monostate{};
}

Result<BodyId> World::CreateBody(const BodyDef& def) {
  if (std::string error = CheckBodyDef(def); !error.empty()) return Error{error};
  // Mass data from the shape and density when asked for, else as given.
  const bool dynamic = def.type == BodyType::Dynamic;
  double mass = def.mass;
  Mat3 inertia = def.localInertia;
  Vec3 localCenter = def.localCenterOfMass;
  if (dynamic && def.shape && def.density > 0.0) {
    const Result<MassProperties> props = def.shape->ComputeMass(def.density);
    if (!props) return Error{"BodyDef.shape mass properties: " + props.GetError().message};
    mass = props.Value().mass;
    inertia = props.Value().inertia;
    localCenter = props.Value().centerOfMass;
    if (!(mass > 0.0) || Eigen::LLT<Mat3>(inertia).info() != Eigen::Success) {
      return Error{"BodyDef.shape at density " + std::to_string(def.density) +
                   " kg/m^3 gives no positive mass and inertia"};
    }
  }
  WorldData& d = *m_data;
  std::int32_t index = 0;
  if (!d.freeSlots.empty()) {
    index = d.freeSlots.back();
    d.freeSlots.pop_back();
  } else {
    index = static_cast<std::int32_t>(d.sims.size());
    d.sims.emplace_back();
    d.sleep.emplace_back();
    d.records.emplace_back();
    d.shapes.emplace_back();
  }
  const std::size_t i = static_cast<std::size_t>(index);

  BodySim sim;
  sim.type = def.type;
  sim.orientation = def.orientation.normalized();
  sim.localCenter = localCenter;
  sim.center = def.position + sim.orientation * localCenter;
  if (def.type != BodyType::Static) {
    sim.linearVelocity = def.linearVelocity;
    sim.angularVelocity = def.angularVelocity;
  }
  if (dynamic) {
    sim.invMass = 1.0 / mass;
    sim.inertiaLocal = inertia;
    sim.invInertiaLocal = inertia.inverse();
    const PrincipalAxes principal = ComputePrincipalAxes(inertia);
    sim.principalFrame = principal.frame;
    sim.principalInertia = principal.moments;
  }
  sim.UpdateWorldInertia();
  d.sims[i] = sim;
  d.sleep[i] = SleepState{.restTime = 0.0, .allowSleep = def.allowSleep};

  BodyRecord& record = d.records[i];
  record.alive = true;
  record.friction = def.friction;
  record.restitution = def.restitution;
  record.mass = dynamic ? mass : 0.0;
  record.localInertia = dynamic ? inertia : Mat3::Zero();
  d.shapes[i] = def.shape;
  ++d.liveBodies;
  return BodyId{index, record.generation};
}

bool World::IsValid(BodyId id) const {
  const WorldData& d = *m_data;
  if (id.index < 0 || static_cast<std::size_t>(id.index) >= d.records.size()) return false;
  const BodyRecord& record = d.records[static_cast<std::size_t>(id.index)];
  return record.alive && record.generation == id.generation;
}

namespace {

std::string StaleMessage(BodyId id) {
  return "body id {index " + std::to_string(id.index) + ", generation " + std::to_string(id.generation) +
         "} does not name a live body (destroyed or never created)";
}

// Removes the contacts of body `index` and their anchors (the entry at the
// same index of `anchors`), keeping the rest in order and side by side.
void EraseContactsOf(std::vector<Contact>& contacts, std::vector<ManifoldAnchors>& anchors, int index) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    if (contacts[i].bodyA == index || contacts[i].bodyB == index) continue;
    if (kept != i) {
      contacts[kept] = contacts[i];
      anchors[kept] = anchors[i];
    }
    ++kept;
  }
  contacts.resize(kept);
  anchors.resize(kept);
}

}  // namespace

Status World::DestroyBody(BodyId id) {
  if (!IsValid(id)) return Refuse(StaleMessage(id));
  WorldData& d = *m_data;
  const std::size_t i = static_cast<std::size_t>(id.index);
  // Whatever touched the body loses its support: wake it.
  for (const Contact& c : d.contacts) {
    if (c.bodyA == id.index) WakeBody(d, static_cast<std::size_t>(c.bodyB));
    if (c.bodyB == id.index) WakeBody(d, static_cast<std::size_t>(c.bodyA));
  }
  EraseContactsOf(d.contacts, d.contactAnchors, id.index);
  // The SAT caches of its pairs name its hull: a new body in the slot must
  // not inherit them.
  const auto involves = [index = id.index](const PairSatCache& c) {
    return static_cast<int>(c.pairKey >> 32) == index || static_cast<int>(c.pairKey & 0xffffffffu) == index;
  };
  std::erase_if(d.satCaches, involves);
  std::erase_if(d.previousSatCaches, involves);
  d.records[i].alive = false;
  ++d.records[i].generation;
  d.sims[i] = BodySim{};
  d.sims[i].awake = false;
  d.sleep[i] = SleepState{};
  d.shapes[i].reset();
  d.freeSlots.push_back(id.index);
  --d.liveBodies;
  return std::monostate{};
}

int World::BodyCount() const { return m_data->liveBodies; }

std::vector<BodyId> World::BodyIds() const {
  std::vector<BodyId> ids;
  ids.reserve(static_cast<std::size_t>(m_data->liveBodies));
  for (std::size_t i = 0; i < m_data->records.size(); ++i) {
    if (m_data->records[i].alive)
      ids.push_back({static_cast<std::int32_t>(i), m_data->records[i].generation});
  }
  return ids;
}

Result<BodyState> World::GetBodyState(BodyId id) const {
  if (!IsValid(id)) return Error{StaleMessage(id)};
  const std::size_t i = static_cast<std::size_t>(id.index);
  const BodySim& sim = m_data->sims[i];
  const BodyRecord& record = m_data->records[i];
  return BodyState{.type = sim.type,
                   .position = sim.Origin(),
                   .orientation = sim.orientation,
                   .centerOfMass = sim.center,
                   .linearVelocity = sim.linearVelocity,
                   .angularVelocity = sim.angularVelocity,
                   .mass = record.mass,
                   .localInertia = record.localInertia,
                   .awake = sim.type != BodyType::Dynamic || sim.awake};
}

namespace {

// Refuses a stale id or a non-finite vector, naming the call and argument.
std::string CheckCall(const World& world, BodyId id, const char* what, const Vec3& value) {
  if (!world.IsValid(id)) return StaleMessage(id);
  if (!Finite(value)) return std::string(what) + " " + Describe(value) + " is not finite";
  return {};
}

}  // namespace

Status World::SetTransform(BodyId id, const Vec3& position, const Quat& orientation) {
  if (std::string e = CheckCall(*this, id, "SetTransform position", position); !e.empty()) return Refuse(e);
  if (!orientation.coeffs().allFinite() || orientation.norm() < 1e-12) {
    return Refuse("SetTransform orientation is not a finite non-zero quaternion");
  }
  const std::size_t i = static_cast<std::size_t>(id.index);
  BodySim& sim = m_data->sims[i];
  sim.orientation = orientation.normalized();
  sim.center = position + sim.orientation * sim.localCenter;
  sim.UpdateWorldInertia();
  sim.keptAngularVelocity.setConstant(std::numeric_limits<double>::quiet_NaN());
  WakeBody(*m_data, i);
  return std::monostate{};
}

Status World::SetLinearVelocity(BodyId id, const Vec3& velocity) {
  if (std::string e = CheckCall(*this, id, "SetLinearVelocity velocity", velocity); !e.empty())
    return Refuse(e);
  const std::size_t i = static_cast<std::size_t>(id.index);
  if (m_data->sims[i].type == BodyType::Static) return std::monostate{};
  m_data->sims[i].linearVelocity = velocity;
  WakeBody(*m_data, i);
  return std::monostate{};
}

Status World::SetAngularVelocity(BodyId id, const Vec3& velocity) {
  if (std::string e = CheckCall(*this, id, "SetAngularVelocity velocity", velocity); !e.empty())
    return Refuse(e);
  const std::size_t i = static_cast<std::size_t>(id.index);
  if (m_data->sims[i].type == BodyType::Static) return std::monostate{};
  m_data->sims[i].angularVelocity = velocity;
  WakeBody(*m_data, i);
  return std::monostate{};
}

Status World::ApplyForce(BodyId id, const Vec3& force, const Vec3& worldPoint) {
  if (std::string e = CheckCall(*this, id, "ApplyForce force", force); !e.empty()) return Refuse(e);
  if (!Finite(worldPoint)) return Refuse("ApplyForce point " + Describe(worldPoint) + " is not finite");
  const std::size_t i = static_cast<std::size_t>(id.index);
  BodySim& sim = m_data->sims[i];
  if (sim.type != BodyType::Dynamic) return std::monostate{};
  // Huge finite inputs can still overflow the sums: refuse those too.
  const Vec3 newForce = sim.force + force;
  const Vec3 newTorque = sim.torque + (worldPoint - sim.center).cross(force);
  if (!Finite(newForce) || !Finite(newTorque))
    return Refuse("ApplyForce: accumulated force or torque overflows");
  sim.force = newForce;
  sim.torque = newTorque;
  WakeBody(*m_data, i);
  return std::monostate{};
}

Status World::ApplyForceToCenter(BodyId id, const Vec3& force) {
  if (!IsValid(id)) return Refuse(StaleMessage(id));
  return ApplyForce(id, force, m_data->sims[static_cast<std::size_t>(id.index)].center);
}

Status World::ApplyTorque(BodyId id, const Vec3& torque) {
  if (std::string e = CheckCall(*this, id, "ApplyTorque torque", torque); !e.empty()) return Refuse(e);
  const std::size_t i = static_cast<std::size_t>(id.index);
  if (m_data->sims[i].type != BodyType::Dynamic) return std::monostate{};
  const Vec3 newTorque = m_data->sims[i].torque + torque;
  if (!Finite(newTorque)) return Refuse("ApplyTorque: accumulated torque overflows");
  m_data->sims[i].torque = newTorque;
  WakeBody(*m_data, i);
  return std::monostate{};
}

Status World::ApplyLinearImpulse(BodyId id, const Vec3& impulse, const Vec3& worldPoint) {
  if (std::string e = CheckCall(*this, id, "ApplyLinearImpulse impulse", impulse); !e.empty())
    return Refuse(e);
  if (!Finite(worldPoint))
    return Refuse("ApplyLinearImpulse point " + Describe(worldPoint) + " is not finite");
  const std::size_t i = static_cast<std::size_t>(id.index);
  BodySim& sim = m_data->sims[i];
  if (sim.type != BodyType::Dynamic) return std::monostate{};
  const Vec3 v = sim.linearVelocity + sim.invMass * impulse;
  const Vec3 w = sim.angularVelocity + sim.invInertiaWorld * (worldPoint - sim.center).cross(impulse);
  if (!Finite(v) || !Finite(w)) return Refuse("ApplyLinearImpulse: resulting velocity overflows");
  sim.linearVelocity = v;
  sim.angularVelocity = w;
  WakeBody(*m_data, i);
  return std::monostate{};
}

Status World::ApplyAngularImpulse(BodyId id, const Vec3& impulse) {
  if (std::string e = CheckCall(*this, id, "ApplyAngularImpulse impulse", impulse); !e.empty())
    return Refuse(e);
  const std::size_t i = static_cast<std::size_t>(id.index);
  BodySim& sim = m_data->sims[i];
  if (sim.type != BodyType::Dynamic) return std::monostate{};
  const Vec3 w = sim.angularVelocity + sim.invInertiaWorld * impulse;
  if (!Finite(w)) return Refuse("ApplyAngularImpulse: resulting angular velocity overflows");
  sim.angularVelocity = w;
  WakeBody(*m_data, i);
  return std::monostate{};
}

}  // namespace talus
