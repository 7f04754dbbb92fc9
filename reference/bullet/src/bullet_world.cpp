// One Bullet world behind the Backend interface (see bullet_world.h): written
// once against btScalar and compiled twice, in double precision into
// talus_bullet_backend and in single precision into the talus_bullet_f32
// module.
//
// Frames: a btRigidBody's transform is its centre-of-mass frame on principal
// axes. A scenario body frame F (origin p, rotation R) maps to it by
// X_com = p + R c and R_com = R P, with c the centroid and P the principal
// rotation from ComputeBodyMass; hull points are stored in that frame as
// P^T (x - c). Reading back inverts it: R = R_com P^T, p = X_com - R c.
//
// Material combining: Bullet multiplies friction and restitution. Each body
// carries CF_CUSTOM_MATERIAL_CALLBACK and a pointer to its Material; the
// process-wide gContactAddedCallback (installed once per Bullet library,
// identical for every world) recomputes both with the scenario's rules for
// every new or refreshed contact point.
#include "bullet_world.h"

#include <btBulletDynamicsCommon.h>

#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <LinearMath/btConvexHullComputer.h>
#include <mutex>
#include <sstream>

#include "talus/harness/scenario/applied_loads.h"
#include "talus/reference/body_mass.h"
#include "talus/reference/setting_text.h"

namespace talus::reference {
namespace {

using harness::BodySpec;
using harness::Run;
using harness::Setting;

constexpr bool kSinglePrecision = sizeof(btScalar) == sizeof(float);

btVector3 ToBt(const Vec3& v) { return btVector3(v.x(), v.y(), v.z()); }
Vec3 FromBt(const btVector3& v) { return Vec3(v.x(), v.y(), v.z()); }
btQuaternion ToBt(const Quat& q) { return btQuaternion(q.x(), q.y(), q.z(), q.w()); }
Quat FromBt(const btQuaternion& q) { return Quat(q.w(), q.x(), q.y(), q.z()); }

// What the contact callback needs to know about a body.
struct Material {
  double friction = 0.0;
  double restitution = 0.0;
  const harness::WorldSpec* world = nullptr;  // the combine rules
  const BulletHost* host = nullptr;           // applies them
};

bool CombineMaterials(btManifoldPoint& point, const btCollisionObjectWrapper* wrap0, int, int,
                      const btCollisionObjectWrapper* wrap1, int, int) {
  const auto* a = static_cast<const Material*>(wrap0->getCollisionObject()->getUserPointer());
  const auto* b = static_cast<const Material*>(wrap1->getCollisionObject()->getUserPointer());
  if (a == nullptr || b == nullptr) return false;
  point.m_combinedFriction =
      static_cast<btScalar>(a->host->combine(a->world->frictionCombine, a->friction, b->friction));
  point.m_combinedRestitution =
      static_cast<btScalar>(a->host->combine(a->world->restitutionCombine, a->restitution, b->restitution));
  return true;
}

class BulletBackend final : public harness::Backend {
 public:
  static Result<std::unique_ptr<harness::Backend>> Create(const Run& run, const std::vector<BodyMass>& masses,
                                                          BulletTuning tuning, const BulletHost& host);
  ~BulletBackend() override;

  [[nodiscard]] std::string Name() const override {
    return std::string(kSinglePrecision ? "bullet-f32" : "bullet") +
           (m_tuning == BulletTuning::Tuned ? "-tuned" : "");
  }
  void Step() override;
  [[nodiscard]] int BodyCount() const override { return static_cast<int>(m_bodies.size()); }
  [[nodiscard]] harness::BodyReading GetBodyState(int index) const override;
  [[nodiscard]] std::vector<harness::ContactReading> GetContacts() const override;
  [[nodiscard]] std::vector<harness::Setting> Settings() const override { return m_settings; }

 private:
  struct Body {
    std::unique_ptr<btCollisionShape> shape;
    std::unique_ptr<btDefaultMotionState> motionState;
    std::unique_ptr<btRigidBody> body;
    Material material;
    BodyMass mass;
    const BodySpec* spec = nullptr;  // the run's, for a kinematic body's prescribed motion
  };

  BulletBackend() = default;
  void AddSettings(const Run& run);

  double m_timeStep = 0.0;
  BulletTuning m_tuning = BulletTuning::Defaults;
  BulletHost m_host;
  harness::WorldSpec m_worldSettings;
  std::unique_ptr<btDefaultCollisionConfiguration> m_configuration;
  std::unique_ptr<btCollisionDispatcher> m_dispatcher;
  std::unique_ptr<btBroadphaseInterface> m_broadphase;
  std::unique_ptr<btSequentialImpulseConstraintSolver> m_solver;
  std::unique_ptr<btDiscreteDynamicsWorld> m_world;
  std::vector<std::unique_ptr<Body>> m_bodies;  // stable addresses: Material is pointed to
  std::vector<harness::Setting> m_settings;
  std::vector<harness::BodySpec> m_specs;           // the run's bodies (kinematic motion)
  std::vector<harness::AppliedLoad> m_loads;        // the scenario's, applied each step
  std::vector<harness::AppliedImpulse> m_impulses;  // the scenario's, each at its step
  long long m_stepIndex = 0;                        // steps taken
};

// The hull's points in the centre-of-mass frame on principal axes. Tuned:
// the hull shrunk by the collision margin first, so that the shape Bullet
// collides (the points' hull plus the margin all round) is the scenario's
// hull with its edges rounded by the margin, not the hull grown by it.
// Bullet's own practice: its ConvexDecompositionDemo moves every face plane
// in by the margin ("due to collision margin, convex objects overlap,
// compensate for it here"); btConvexHullComputer's shrink does the same
// ("each face is moved by shrink length units towards the center along its
// normal") exactly, where btGeometryUtil's plane search has fixed 1 cm and
// 2.6 degree tolerances.
Result<std::vector<btVector3>> HullPoints(const BodySpec& spec, const BodyMass& mass, BulletTuning tuning) {
  const Mat3 toPrincipal = mass.principalRotation.toRotationMatrix().transpose();
  std::vector<btVector3> points;
  for (const Vec3& point : std::get<harness::HullShape>(spec.shape).points) {
    points.push_back(ToBt(toPrincipal * (point - mass.centroid)));
  }
  if (tuning == BulletTuning::Defaults) return points;
  btConvexHullComputer shrunk;
  const btScalar margin = static_cast<btScalar>(kBulletCollisionMargin);
  const btScalar moved = shrunk.compute(&points[0].getX(), static_cast<int>(sizeof(btVector3)),
                                        static_cast<int>(points.size()), margin, btScalar(0));
  // The computer returns the distance it moved the faces: less than the
  // margin (or negative) when the hull is thinner than twice the margin.
  if (!(moved >= margin) || shrunk.vertices.size() < 4) {
    return Error{"body \"" + spec.name + "\": the hull is too thin to shrink by the " +
                 SettingNumber(kBulletCollisionMargin) +
                 " m collision margin (btConvexHullComputer moved its faces " +
                 SettingNumber(static_cast<double>(moved)) + " m)"};
  }
  return std::vector<btVector3>(&shrunk.vertices[0], &shrunk.vertices[0] + shrunk.vertices.size());
}

Result<std::unique_ptr<btCollisionShape>> MakeShape(const BodySpec& spec, const BodyMass& mass,
                                                    BulletTuning tuning) {
  std::unique_ptr<btCollisionShape> shape;
  if (const auto* box = std::get_if<harness::BoxShape>(&spec.shape)) {
    shape = std::make_unique<btBoxShape>(ToBt(box->halfExtents));
  } else if (const auto* sphere = std::get_if<harness::SphereShape>(&spec.shape)) {
    // A sphere's margin is its radius; setMargin would change nothing.
    return std::unique_ptr<btCollisionShape>(std::make_unique<btSphereShape>(sphere->radius));
  } else {
    auto points = HullPoints(spec, mass, tuning);
    if (!points) return points.GetError();
    auto hull = std::make_unique<btConvexHullShape>();
    for (const btVector3& point : points.Value()) hull->addPoint(point, false);
    hull->recalcLocalAabb();
    shape = std::move(hull);
  }
  // Defaults keep Bullet's own margin (CONVEX_DISTANCE_MARGIN, 0.04 m).
  if (tuning == BulletTuning::Tuned) shape->setMargin(kBulletCollisionMargin);
  if (auto* hull = dynamic_cast<btConvexHullShape*>(shape.get())) hull->initializePolyhedralFeatures();
  return shape;
}

Result<std::unique_ptr<harness::Backend>> BulletBackend::Create(const Run& run,
                                                                const std::vector<BodyMass>& masses,
                                                                BulletTuning tuning, const BulletHost& host) {
  if (masses.size() != run.scenario.bodies.size()) {
    return Error{"bullet: " + std::to_string(masses.size()) + " mass records for " +
                 std::to_string(run.scenario.bodies.size()) + " bodies"};
  }
  static std::once_flag installCallback;
  std::call_once(installCallback, [] { gContactAddedCallback = CombineMaterials; });

  std::unique_ptr<BulletBackend> backend(new BulletBackend());
  backend->m_timeStep = run.timeStep;
  backend->m_tuning = tuning;
  backend->m_host = host;
  backend->m_worldSettings = run.scenario.world;
  backend->m_configuration = std::make_unique<btDefaultCollisionConfiguration>();
  backend->m_dispatcher = std::make_unique<btCollisionDispatcher>(backend->m_configuration.get());
  backend->m_broadphase = std::make_unique<btDbvtBroadphase>();
  backend->m_solver = std::make_unique<btSequentialImpulseConstraintSolver>();
  backend->m_world =
      std::make_unique<btDiscreteDynamicsWorld>(backend->m_dispatcher.get(), backend->m_broadphase.get(),
                                                backend->m_solver.get(), backend->m_configuration.get());
  btDiscreteDynamicsWorld& world = *backend->m_world;
  world.setGravity(ToBt(run.scenario.world.gravity));
  btContactSolverInfo& info = world.getSolverInfo();
  info.m_numIterations = run.iterations > 0 ? run.iterations : kBulletDefaultIterations;
  // Bullet's own default, set so the record does not depend on the version.
  info.m_restitutionVelocityThreshold = static_cast<btScalar>(kRestitutionVelocityThreshold);

  backend->m_specs = run.scenario.bodies;
  backend->m_loads = run.scenario.loads;
  backend->m_impulses = run.scenario.impulses;
  for (size_t i = 0; i < run.scenario.bodies.size(); ++i) {
    const BodySpec& spec = run.scenario.bodies[i];
    auto body = std::make_unique<Body>();
    body->spec = &backend->m_specs[i];
    body->mass = masses[i];
    body->material = {spec.friction, spec.restitution, &backend->m_worldSettings, &backend->m_host};
    auto shape = MakeShape(spec, body->mass, tuning);
    if (!shape)
      return Error{std::string(kSinglePrecision ? "bullet-f32" : "bullet") + ": " + shape.GetError().message};
    body->shape = std::move(shape).Value();
    const Mat3 rotation = spec.orientation.toRotationMatrix();
    const Vec3 com = spec.position + rotation * body->mass.centroid;
    const Quat comOrientation = (spec.orientation * body->mass.principalRotation).normalized();
    body->motionState = std::make_unique<btDefaultMotionState>(btTransform(ToBt(comOrientation), ToBt(com)));
    const bool dynamic = spec.motion == harness::Motion::Dynamic;
    btRigidBody::btRigidBodyConstructionInfo construction(
        dynamic ? body->mass.mass : 0.0, body->motionState.get(), body->shape.get(),
        dynamic ? ToBt(body->mass.principalInertia) : btVector3(0, 0, 0));
    construction.m_friction = spec.friction;
    construction.m_restitution = spec.restitution;
    construction.m_linearDamping = 0.0;
    construction.m_angularDamping = 0.0;
    body->body = std::make_unique<btRigidBody>(construction);
    btRigidBody& rigid = *body->body;
    // The gyroscopic term as the scenario says, in Bullet's implicit body-frame
    // form only (the explicit and implicit-world variants always cleared).
    int flags =
        rigid.getFlags() & ~(BT_ENABLE_GYROSCOPIC_FORCE_EXPLICIT | BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_WORLD |
                             BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY);
    if (run.scenario.world.gyroscopic) flags |= BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY;
    rigid.setFlags(flags);
    rigid.setCollisionFlags(rigid.getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
    rigid.setUserPointer(&body->material);
    rigid.setUserIndex(static_cast<int>(i));
    rigid.setActivationState(DISABLE_DEACTIVATION);
    if (spec.motion == harness::Motion::Kinematic) {
      // Bullet's kinematic body: mass 0 (infinite to contacts), moved by
      // its motion state, from which stepSimulation derives the velocity
      // the contacts see (Step).
      rigid.setCollisionFlags(rigid.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
    }
    if (dynamic) {
      rigid.setLinearVelocity(ToBt(spec.linearVelocity));
      rigid.setAngularVelocity(ToBt(spec.angularVelocity));
    }
    world.addRigidBody(&rigid);
    backend->m_bodies.push_back(std::move(body));
  }
  backend->AddSettings(run);
  return std::unique_ptr<harness::Backend>(std::move(backend));
}

// One step as a Bullet user drives it: each kinematic body's motion state
// set to its prescribed pose at the step's end (stepSimulation's
// saveKinematicState turns the change into the velocity the contacts
// see), the impulses due now through applyImpulse, each load's share of
// the step through applyForce (at a point) or applyCentralForce and
// applyTorque, then one stepSimulation, which clears the forces.
void BulletBackend::Step() {
  const double t = static_cast<double>(m_stepIndex) * m_timeStep;
  for (auto& body : m_bodies) {
    if (body->spec->motion != harness::Motion::Kinematic) continue;
    const harness::KinematicPose pose = harness::KinematicPoseAt(*body->spec, t + m_timeStep);
    const Vec3 com = pose.origin + pose.orientation.toRotationMatrix() * body->mass.centroid;
    const Quat comOrientation = (pose.orientation * body->mass.principalRotation).normalized();
    body->motionState->setWorldTransform(btTransform(ToBt(comOrientation), ToBt(com)));
  }
  for (const harness::AppliedImpulse& impulse : m_impulses) {
    if (!harness::AppliedImpulseAtStep(impulse, m_stepIndex, m_timeStep)) continue;
    const harness::BodyReading state = GetBodyState(impulse.body);
    btRigidBody& rigid = *m_bodies[static_cast<size_t>(impulse.body)]->body;
    if (const auto point = harness::ImpulseWorldPoint(impulse, state.origin, state.orientation)) {
      rigid.applyImpulse(ToBt(impulse.linear), ToBt(*point - state.centerOfMass));
    } else {
      rigid.applyCentralImpulse(ToBt(impulse.linear));
    }
  }
  for (const harness::AppliedLoad& load : m_loads) {
    const double share = harness::AppliedLoadShare(load, t, m_timeStep);
    if (share == 0.0) continue;
    const harness::BodyReading state = GetBodyState(load.body);
    const harness::WorldLoad world = harness::ToWorldLoad(load, share, state.origin, state.orientation);
    btRigidBody& rigid = *m_bodies[static_cast<size_t>(load.body)]->body;
    if (world.point) {
      rigid.applyForce(ToBt(world.force), ToBt(*world.point - state.centerOfMass));
    } else {
      rigid.applyCentralForce(ToBt(world.force));
    }
    rigid.applyTorque(ToBt(world.torque));
  }
  m_world->stepSimulation(m_timeStep, 0);
  ++m_stepIndex;
}

BulletBackend::~BulletBackend() {
  for (auto& body : m_bodies) m_world->removeRigidBody(body->body.get());
}

void BulletBackend::AddSettings(const Run& run) {
  const btContactSolverInfo& info = m_world->getSolverInfo();
  const bool tuned = m_tuning == BulletTuning::Tuned;
  const std::string version = "Bullet " + std::to_string(btGetVersion());
  m_settings = {
      {"configuration", tuned ? "tuned (collision margin scaled to the scene's bodies, hulls shrunk by it)"
                              : "defaults (what a new Bullet user gets)"},
      kSinglePrecision
          ? Setting{"engine", version + " (single precision: the default build, pkg-config bullet)"}
          : Setting{"engine",
                    version + " (double precision: BT_USE_DOUBLE_PRECISION, pkg-config bullet-float64)",
                    "single precision (pkg-config bullet, what most users link)", kBulletDoubleEffect},
      {"world", "btDiscreteDynamicsWorld, btDbvtBroadphase, btDefaultCollisionConfiguration"},
      {"solver", "btSequentialImpulseConstraintSolver"},
      {"time step (s)", SettingNumber(run.timeStep)},
      {"stepping", "stepSimulation(h, 0): exactly one internal step of h per Step, no interpolation",
       "stepSimulation(dt, 1, 1/60): fixed 1/60 s substeps, interpolated motion states",
       "needed to pose the run's time step: every engine takes one step of h per Step"},
      {"integrator", "semi-implicit (symplectic) Euler: v += h a, then x += h v"},
      {"solver iterations",
       std::to_string(info.m_numIterations) + (run.iterations > 0 ? "" : " (engine default)")},
      {"solver mode flags",
       std::to_string(info.m_solverMode) + " (warm starting, SIMD; one friction direction)"},
      {"warm starting factor", SettingNumber(info.m_warmstartingFactor)},
      {"split impulse", std::to_string(info.m_splitImpulse) + " (on past a penetration of " +
                            SettingNumber(-info.m_splitImpulsePenetrationThreshold) + " m)"},
      {"erp2 (contact Baumgarte factor)", SettingNumber(info.m_erp2)},
      {"linear slop (m)", SettingNumber(info.m_linearSlop)},
      {"global cfm", SettingNumber(info.m_globalCfm)},
      {"restitution velocity threshold (m/s)", SettingNumber(info.m_restitutionVelocityThreshold)},
      {"friction combine",
       std::string(m_host.combineName(run.scenario.world.frictionCombine)) +
           " (gContactAddedCallback, CF_CUSTOM_MATERIAL_CALLBACK)",
       "product mu_a mu_b",
       "needed to pose the scenario's rule: with the product, mu = 0.5 on both bodies is 0.25"},
      {"restitution combine", m_host.combineName(run.scenario.world.restitutionCombine), "product e_a e_b",
       "needed to pose the scenario's rule (max by default): a sphere with e = 0.7 on a floor with e = 0 "
       "would not bounce"},
      tuned ? Setting{"collision margin (m)",
                      SettingNumber(kBulletCollisionMargin) +
                          " (boxes exact, hulls shrunk by it first so hull + margin is the hull with rounded "
                          "edges, spheres: radius)",
                      "0.04 (CONVEX_DISTANCE_MARGIN)", kBulletMarginEffect}
            : Setting{"collision margin (m)",
                      "0.04 (boxes exact with corners rounded by it, hulls inflated by "
                      "it, spheres: radius)"},
      {"contact breaking threshold (m)", SettingNumber(gContactBreakingThreshold)},
      run.scenario.world.gyroscopic
          ? Setting{"gyroscopic term", "on (BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY)"}
          : Setting{"gyroscopic term", "off (BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY cleared)",
                    "on (BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY)",
                    "the scenario asks for no gyroscopic term (angular velocity exactly constant)"},
      {"damping", "linear 0, angular 0"},
      {"sleeping", "off (DISABLE_DEACTIVATION)", "on (a body still for 2 s below 0.8 m/s and 1 rad/s sleeps)",
       "needed to measure the engine: a sleeping body is frozen, which would hide the jitter and drift "
       "the rest and stacking truths measure (Talus and ODE do not sleep either)"},
      {"max rotation per step (rad)", SettingNumber(0.25 * SIMD_PI) + " (Bullet clamps faster spins)"},
      tuned
          ? Setting{"hull shapes",
                    "btConvexHullShape of the hull shrunk by the margin (btConvexHullComputer shrink), with "
                    "initializePolyhedralFeatures, centred on the centroid",
                    "btConvexHullShape of the points (grown by the margin)", kBulletHullShrinkEffect}
          : Setting{"hull shapes",
                    "btConvexHullShape with initializePolyhedralFeatures, centred on the centroid"},
      {"mass properties", "from talus::reference::ComputeBodyMass (exact), principal axes"},
  };
  // Listed only where the scenario uses them, so other runs' records stay as they were.
  if (!run.scenario.loads.empty() || !run.scenario.impulses.empty()) {
    m_settings.push_back({"loads and impulses",
                          "applyForce (at a point) or applyCentralForce and applyTorque before each "
                          "stepSimulation, scaled by the step's share of the window; applyImpulse at the "
                          "impulse's step"});
  }
  for (const BodySpec& spec : run.scenario.bodies) {
    if (spec.motion != harness::Motion::Kinematic) continue;
    m_settings.push_back({"kinematic bodies",
                          "mass 0 with CF_KINEMATIC_OBJECT; the motion state set to the prescribed pose at "
                          "each step's end, stepSimulation deriving the contacts' velocity from it"});
    break;
  }
}

harness::BodyReading BulletBackend::GetBodyState(int index) const {
  const Body& body = *m_bodies.at(static_cast<size_t>(index));
  const btTransform& transform = body.body->getCenterOfMassTransform();
  harness::BodyReading state;
  state.centerOfMass = FromBt(transform.getOrigin());
  const Quat comOrientation = FromBt(transform.getRotation());
  state.orientation = (comOrientation * body.mass.principalRotation.conjugate()).normalized();
  state.origin = state.centerOfMass - state.orientation.toRotationMatrix() * body.mass.centroid;
  state.linearVelocity = FromBt(body.body->getLinearVelocity());
  state.angularVelocity = FromBt(body.body->getAngularVelocity());
  state.mass = body.mass.mass;
  const Mat3 rotation = state.orientation.toRotationMatrix();
  state.worldInertia = rotation * body.mass.inertia * rotation.transpose();
  return state;
}

std::vector<harness::ContactReading> BulletBackend::GetContacts() const {
  // Bullet keeps points up to the breaking threshold apart; all are
  // reported, with depth = -distance (negative when separated).
  std::vector<harness::ContactReading> contacts;
  const int manifolds = m_dispatcher->getNumManifolds();
  for (int m = 0; m < manifolds; ++m) {
    const btPersistentManifold* manifold = m_dispatcher->getManifoldByIndexInternal(m);
    const int bodyA = manifold->getBody0()->getUserIndex();
    const int bodyB = manifold->getBody1()->getUserIndex();
    for (int p = 0; p < manifold->getNumContacts(); ++p) {
      const btManifoldPoint& point = manifold->getContactPoint(p);
      contacts.push_back({bodyA, bodyB, FromBt(point.getPositionWorldOnB()), FromBt(point.m_normalWorldOnB),
                          -point.getDistance()});
    }
  }
  return contacts;
}

}  // namespace

Result<std::unique_ptr<harness::Backend>> CreateBulletWorld(const Run& run,
                                                            const std::vector<BodyMass>& masses,
                                                            BulletTuning tuning, const BulletHost& host) {
  return BulletBackend::Create(run, masses, tuning, host);
}

}  // namespace talus::reference
