// Bullet behind the Backend interface (see talus/reference/bullet_backend.h).
//
// Frames: a btRigidBody's transform is its centre-of-mass frame on principal
// axes. A scenario body frame F (origin p, rotation R) maps to it by
// X_com = p + R c and R_com = R P, with c the centroid and P the principal
// rotation from ComputeBodyMass; hull points are stored in that frame as
// P^T (x - c). Reading back inverts it: R = R_com P^T, p = X_com - R c.
//
// Material combining: Bullet multiplies friction and restitution. Each body
// carries CF_CUSTOM_MATERIAL_CALLBACK and a pointer to its Material; the
// process-wide gContactAddedCallback (installed once, identical for every
// world) recomputes both with the scenario's rules for every new or
// refreshed contact point.
#include "talus/reference/bullet_backend.h"

#include <btBulletDynamicsCommon.h>

#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <mutex>
#include <sstream>

#include "talus/reference/body_mass.h"

namespace talus::reference {
namespace {

using harness::BodySpec;
using harness::Run;

btVector3 ToBt(const Vec3& v) { return btVector3(v.x(), v.y(), v.z()); }
Vec3 FromBt(const btVector3& v) { return Vec3(v.x(), v.y(), v.z()); }
btQuaternion ToBt(const Quat& q) { return btQuaternion(q.x(), q.y(), q.z(), q.w()); }
Quat FromBt(const btQuaternion& q) { return Quat(q.w(), q.x(), q.y(), q.z()); }

std::string Format(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

// What the contact callback needs to know about a body.
struct Material {
  double friction = 0.0;
  double restitution = 0.0;
  const harness::WorldSettings* world = nullptr;  // the combine rules
};

bool CombineMaterials(btManifoldPoint& point, const btCollisionObjectWrapper* wrap0, int, int,
                      const btCollisionObjectWrapper* wrap1, int, int) {
  const auto* a = static_cast<const Material*>(wrap0->getCollisionObject()->getUserPointer());
  const auto* b = static_cast<const Material*>(wrap1->getCollisionObject()->getUserPointer());
  if (a == nullptr || b == nullptr) return false;
  point.m_combinedFriction = harness::Combine(a->world->frictionCombine, a->friction, b->friction);
  point.m_combinedRestitution =
      harness::Combine(a->world->restitutionCombine, a->restitution, b->restitution);
  return true;
}

class BulletBackend final : public harness::Backend {
 public:
  static Result<std::unique_ptr<harness::Backend>> Create(const Run& run);
  ~BulletBackend() override;

  [[nodiscard]] std::string Name() const override { return "bullet"; }
  void Step() override { m_world->stepSimulation(m_timeStep, 0); }
  [[nodiscard]] int BodyCount() const override { return static_cast<int>(m_bodies.size()); }
  [[nodiscard]] harness::BodyState GetBodyState(int index) const override;
  [[nodiscard]] std::vector<harness::ContactPoint> GetContacts() const override;
  [[nodiscard]] std::vector<harness::Setting> Settings() const override { return m_settings; }

 private:
  struct Body {
    std::unique_ptr<btCollisionShape> shape;
    std::unique_ptr<btDefaultMotionState> motionState;
    std::unique_ptr<btRigidBody> body;
    Material material;
    BodyMass mass;
  };

  BulletBackend() = default;
  void AddSettings(const Run& run);

  double m_timeStep = 0.0;
  harness::WorldSettings m_worldSettings;
  std::unique_ptr<btDefaultCollisionConfiguration> m_configuration;
  std::unique_ptr<btCollisionDispatcher> m_dispatcher;
  std::unique_ptr<btBroadphaseInterface> m_broadphase;
  std::unique_ptr<btSequentialImpulseConstraintSolver> m_solver;
  std::unique_ptr<btDiscreteDynamicsWorld> m_world;
  std::vector<std::unique_ptr<Body>> m_bodies;  // stable addresses: Material is pointed to
  std::vector<harness::Setting> m_settings;
};

std::unique_ptr<btCollisionShape> MakeShape(const BodySpec& spec, const BodyMass& mass) {
  std::unique_ptr<btCollisionShape> shape;
  if (const auto* box = std::get_if<harness::BoxShape>(&spec.shape)) {
    shape = std::make_unique<btBoxShape>(ToBt(box->halfExtents));
  } else if (const auto* sphere = std::get_if<harness::SphereShape>(&spec.shape)) {
    // A sphere's margin is its radius; setMargin would change nothing.
    return std::make_unique<btSphereShape>(sphere->radius);
  } else {
    auto hull = std::make_unique<btConvexHullShape>();
    const Mat3 toPrincipal = mass.principalRotation.toRotationMatrix().transpose();
    for (const Vec3& point : std::get<harness::HullShape>(spec.shape).points) {
      hull->addPoint(ToBt(toPrincipal * (point - mass.centroid)), false);
    }
    hull->recalcLocalAabb();
    shape = std::move(hull);
  }
  shape->setMargin(kBulletCollisionMargin);
  if (auto* hull = dynamic_cast<btConvexHullShape*>(shape.get())) hull->initializePolyhedralFeatures();
  return shape;
}

Result<std::unique_ptr<harness::Backend>> BulletBackend::Create(const Run& run) {
  // Mass properties first: a bad hull fails before anything is built.
  std::vector<BodyMass> masses;
  for (const BodySpec& spec : run.scenario.bodies) {
    auto mass = ComputeBodyMass(spec);
    if (!mass) return Error{"bullet: " + mass.GetError().message};
    masses.push_back(mass.Value());
  }
  static std::once_flag installCallback;
  std::call_once(installCallback, [] { gContactAddedCallback = CombineMaterials; });

  std::unique_ptr<BulletBackend> backend(new BulletBackend());
  backend->m_timeStep = run.timeStep;
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
  info.m_restitutionVelocityThreshold = kRestitutionVelocityThreshold;
  // Plain Baumgarte position correction, as in the original write-up.
  info.m_splitImpulse = 0;
  info.m_erp2 = 0.2;
  info.m_linearSlop = 0.0;

  for (size_t i = 0; i < run.scenario.bodies.size(); ++i) {
    const BodySpec& spec = run.scenario.bodies[i];
    auto body = std::make_unique<Body>();
    body->mass = masses[i];
    body->material = {spec.friction, spec.restitution, &backend->m_worldSettings};
    body->shape = MakeShape(spec, body->mass);
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

BulletBackend::~BulletBackend() {
  for (auto& body : m_bodies) m_world->removeRigidBody(body->body.get());
}

void BulletBackend::AddSettings(const Run& run) {
  const btContactSolverInfo& info = m_world->getSolverInfo();
  m_settings = {
      {"engine", "Bullet " + std::to_string(btGetVersion()) + " (double precision: BT_USE_DOUBLE_PRECISION)"},
      {"world", "btDiscreteDynamicsWorld, btDbvtBroadphase, btDefaultCollisionConfiguration"},
      {"solver", "btSequentialImpulseConstraintSolver"},
      {"time step (s)", Format(run.timeStep)},
      {"stepping", "stepSimulation(h, 0): exactly one internal step of h per Step, no interpolation"},
      {"integrator", "semi-implicit (symplectic) Euler: v += h a, then x += h v"},
      {"solver iterations",
       std::to_string(info.m_numIterations) + (run.iterations > 0 ? "" : " (engine default)")},
      {"solver mode flags",
       std::to_string(info.m_solverMode) + " (warm starting, SIMD; one friction direction)"},
      {"warm starting factor", Format(info.m_warmstartingFactor)},
      {"split impulse", "off (Baumgarte only)"},
      {"erp2 (contact Baumgarte factor)", Format(info.m_erp2)},
      {"linear slop (m)", Format(info.m_linearSlop)},
      {"global cfm", Format(info.m_globalCfm)},
      {"restitution velocity threshold (m/s)", Format(info.m_restitutionVelocityThreshold)},
      {"friction combine", std::string(harness::CombineRuleName(run.scenario.world.frictionCombine)) +
                               " (gContactAddedCallback, CF_CUSTOM_MATERIAL_CALLBACK)"},
      {"restitution combine", harness::CombineRuleName(run.scenario.world.restitutionCombine)},
      {"collision margin (m)",
       Format(kBulletCollisionMargin) + " (boxes exact, hulls inflated by it, spheres: radius)"},
      {"contact breaking threshold (m)", Format(gContactBreakingThreshold)},
      {"gyroscopic term", run.scenario.world.gyroscopic
                              ? "on (BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY)"
                              : "off (BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY cleared)"},
      {"damping", "linear 0, angular 0"},
      {"sleeping", "off (DISABLE_DEACTIVATION)"},
      {"max rotation per step (rad)", Format(0.25 * SIMD_PI) + " (Bullet clamps faster spins)"},
      {"hull shapes", "btConvexHullShape with initializePolyhedralFeatures, centred on the centroid"},
      {"mass properties", "from talus::reference::ComputeBodyMass (exact), principal axes"},
  };
}

harness::BodyState BulletBackend::GetBodyState(int index) const {
  const Body& body = *m_bodies.at(static_cast<size_t>(index));
  const btTransform& transform = body.body->getCenterOfMassTransform();
  harness::BodyState state;
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

std::vector<harness::ContactPoint> BulletBackend::GetContacts() const {
  // Bullet keeps points up to the breaking threshold apart; all are
  // reported, with depth = -distance (negative when separated).
  std::vector<harness::ContactPoint> contacts;
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

void RegisterBulletBackends(harness::BackendRegistry& registry) {
  registry.Register("bullet", "Bullet 3 (double): discrete dynamics world, sequential impulse solver",
                    BulletBackend::Create);
}

}  // namespace talus::reference
