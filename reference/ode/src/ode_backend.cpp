// ODE behind the Backend interface (see talus/reference/ode_backend.h).
//
// Frames: an ODE body's frame must be its centre of mass, so, as in the
// Bullet backend, bodies sit at X_com = p + R c with rotation R P (c the
// centroid, P the principal rotation from ComputeBodyMass), hull points are
// stored as P^T (x - c), and the scenario frame is recovered on read-back.
// Static bodies are geoms without a body, placed the same way.
//
// One step: the space (dSimpleSpace in `defaults`, dHashSpace in `tuned`)
// reports the pairs whose boxes overlap, and each pair is collided in the
// order and with the geom order the space gives, as an ODE user's near
// callback gets them. Both spaces' orders are a fixed function of the
// world's history (the geom list, which ODE reorders as geoms move, and for
// the hash space its cells), so runs are byte-identical run to run. The
// order matters: dWorldStep's stability on the 4-layer pyramid depends on
// it (measured, tuned: the hash space's own order stands; the same pairs
// sorted by body index lose 3 height truths, sorted in descending order 4
// and the drift), so no order of our own is imposed. Each
// contact becomes a dContact joint with the scenario's combined friction and
// restitution (in `tuned`, the first friction direction along the slip),
// then the world steps and the contact group is emptied.
#include "talus/reference/ode_backend.h"
#include "talus/reference/setting_text.h"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>
#include <utility>

#include "talus/harness/scenario/applied_loads.h"
#include "talus/harness/scenario/scenario_limits.h"
#include "talus/reference/body_mass.h"
#include "talus/reference/ode_hull_faces.h"
#include "talus/reference/point_hull.h"

namespace talus::reference {
namespace {

using harness::BodySpec;
using harness::Run;
using harness::Setting;

// ODE's error reporting. dError and dDebug (its internal assertions, such
// as dxNormalize4's "zero length quaternion") must not return: ODE aborts
// if the handler does, and unwinding a C++ exception or a longjmp through
// ODE's frames would leave its step memory arena and the world half
// updated, so neither can be made a recoverable run failure soundly. The
// backend instead keeps ODE from reaching them (OdeBackend::Step refuses to
// step a world holding a non-finite or out-of-bounds state, the loader and
// ComputeBodyMass refuse extreme sizes, speeds and masses), and these
// handlers name the run before the abort that remains the last resort.
// dMessage (warnings such as "LCP internal error") may return: the last one
// is kept per thread and added to a failed step's reason.
thread_local const std::string* tCurrentRun = nullptr;
thread_local std::string tLastMessage;

std::string FormatOdeMessage(int number, const char* format, va_list arguments) {
  char text[512];
  std::vsnprintf(text, sizeof text, format, arguments);
  return "ODE message " + std::to_string(number) + ": " + text;
}

[[noreturn]] void OdeFatal(const char* kind, int number, const char* format, va_list arguments) {
  std::fprintf(stderr, "ode: run %s: ODE %s %d: ", tCurrentRun != nullptr ? tCurrentRun->c_str() : "(none)",
               kind, number);
  std::vfprintf(stderr, format, arguments);
  std::fprintf(stderr, "\node: ODE cannot continue after an internal error; aborting\n");
  std::abort();
}

void OdeError(int number, const char* format, va_list arguments) {
  OdeFatal("error", number, format, arguments);
}
void OdeDebug(int number, const char* format, va_list arguments) {
  OdeFatal("internal assertion", number, format, arguments);
}
void OdeMessage(int number, const char* format, va_list arguments) {
  tLastMessage = FormatOdeMessage(number, format, arguments);
}

// ODE's library-wide state: initialised on first use, closed at exit.
class OdeLibrary {
 public:
  static const OdeLibrary& Get() {
    static const OdeLibrary library;
    return library;
  }
  [[nodiscard]] bool DoublePrecision() const { return m_double; }
  [[nodiscard]] const std::string& Configuration() const { return m_configuration; }

 private:
  OdeLibrary() {
    dInitODE2(0);
    dAllocateODEDataForThread(dAllocateMaskAll);
    dSetErrorHandler(&OdeError);
    dSetDebugHandler(&OdeDebug);
    dSetMessageHandler(&OdeMessage);
    m_configuration = dGetConfiguration();
    m_double = dCheckConfiguration("ODE_double_precision") != 0;
  }
  ~OdeLibrary() { dCloseODE(); }
  std::string m_configuration;
  bool m_double = false;
};

enum class Stepper { Step, QuickStep };

// What differs between the two configurations (see ode_backend.h).
struct OdeConfig {
  Stepper stepper = Stepper::Step;
  OdeTuning tuning = OdeTuning::Defaults;
};

std::string BackendName(const OdeConfig& config) {
  std::string name = config.stepper == Stepper::Step ? "ode-step" : "ode-quickstep";
  return config.tuning == OdeTuning::Tuned ? name + "-tuned" : name;
}

class OdeBackend final : public harness::Backend {
 public:
  static Result<std::unique_ptr<harness::Backend>> Create(const Run& run, OdeConfig config);
  ~OdeBackend() override;

  [[nodiscard]] std::string Name() const override { return BackendName(m_config); }
  void Step() override;
  [[nodiscard]] int BodyCount() const override { return static_cast<int>(m_bodies.size()); }
  [[nodiscard]] harness::BodyReading GetBodyState(int index) const override;
  [[nodiscard]] std::vector<harness::ContactReading> GetContacts() const override { return m_contacts; }
  [[nodiscard]] std::vector<harness::Setting> Settings() const override { return m_settings; }
  [[nodiscard]] std::string StepFailure() const override { return m_failure; }

 private:
  struct Body {
    int index = -1;
    std::string name;
    double friction = 0.0;
    double restitution = 0.0;
    BodyMass mass;
    bool dynamic = false;
    const BodySpec* spec = nullptr;  // the run's (a kinematic body's prescribed motion)
    dBodyID body = nullptr;          // null for static bodies
    dGeomID geom = nullptr;
    // dConvex keeps pointers into these.
    std::vector<dReal> planes;
    std::vector<dReal> points;
    std::vector<unsigned> polygons;
  };

  OdeBackend() = default;
  static void NearCallback(void* data, dGeomID geom1, dGeomID geom2);
  [[nodiscard]] std::string Collide(const Body& a, const Body& b);
  [[nodiscard]] bool SlipDirection(const Body& a, const Body& b, const dContactGeom& contact,
                                   dVector3 direction) const;
  Result<bool> AddBody(const BodySpec& spec, const BodyMass& mass, int index);
  void AddSettings(const Run& run);
  [[nodiscard]] std::string UnsafeState() const;

  OdeConfig m_config;
  std::string m_runId;    // named by the fatal-error handlers
  std::string m_failure;  // why the last Step failed; empty when it ran
  double m_timeStep = 0.0;
  harness::WorldSpec m_worldSettings;
  dWorldID m_world = nullptr;
  dSpaceID m_space = nullptr;
  dJointGroupID m_contactGroup = nullptr;
  std::vector<std::unique_ptr<Body>> m_bodies;
  std::vector<harness::ContactReading> m_contacts;
  // The pairs the space reported this step, as (geom 1, geom 2) body index.
  std::vector<std::pair<int, int>> m_pairs;
  // This world's stream of ODE's library-wide random generator (quickstep
  // reorders constraints randomly): swapped in around each step, so a world's
  // results do not depend on what other worlds ran before it in the process.
  unsigned long m_randomSeed = 0;
  std::vector<harness::Setting> m_settings;
  std::vector<harness::BodySpec> m_specs;           // the run's bodies
  std::vector<harness::AppliedLoad> m_loads;        // the scenario's, applied each step
  std::vector<harness::AppliedImpulse> m_impulses;  // the scenario's, each at its step
  long long m_stepIndex = 0;                        // steps taken
  void ApplyLoads();
};

Result<bool> OdeBackend::AddBody(const BodySpec& spec, const BodyMass& mass, int index) {
  auto body = std::make_unique<Body>();
  body->index = index;
  body->name = spec.name;
  body->friction = spec.friction;
  body->restitution = spec.restitution;
  body->mass = mass;
  body->dynamic = spec.motion == harness::Motion::Dynamic;
  body->spec = &spec;
  if (const auto* box = std::get_if<harness::BoxShape>(&spec.shape)) {
    const Vec3 size = 2.0 * box->halfExtents;
    body->geom = dCreateBox(m_space, size.x(), size.y(), size.z());
  } else if (const auto* sphere = std::get_if<harness::SphereShape>(&spec.shape)) {
    body->geom = dCreateSphere(m_space, sphere->radius);
  } else {
    const Mat3 toPrincipal = mass.principalRotation.toRotationMatrix().transpose();
    std::vector<Vec3> local;
    for (const Vec3& point : std::get<harness::HullShape>(spec.shape).points) {
      local.push_back(toPrincipal * (point - mass.centroid));
    }
    auto hull = ComputePointHull(local);
    if (!hull) return Error{"ode: body \"" + spec.name + "\": " + hull.GetError().message};
    for (const Vec3& v : hull.Value().vertices)
      body->points.insert(body->points.end(), {v.x(), v.y(), v.z()});
    for (const HullFace& face : OdeHullFaces(hull.Value())) {
      body->planes.insert(body->planes.end(),
                          {face.normal.x(), face.normal.y(), face.normal.z(), face.offset});
      body->polygons.push_back(static_cast<unsigned>(face.corners.size()));
      for (const int corner : face.corners) body->polygons.push_back(static_cast<unsigned>(corner));
    }
    body->geom = dCreateConvex(m_space, body->planes.data(), static_cast<unsigned>(body->planes.size() / 4),
                               body->points.data(), static_cast<unsigned>(body->points.size() / 3),
                               body->polygons.data());
  }
  dGeomSetData(body->geom, body.get());

  const Vec3 com = spec.position + spec.orientation.toRotationMatrix() * mass.centroid;
  const Quat comOrientation = (spec.orientation * mass.principalRotation).normalized();
  const dQuaternion q = {comOrientation.w(), comOrientation.x(), comOrientation.y(), comOrientation.z()};
  if (spec.motion == harness::Motion::Dynamic) {
    body->body = dBodyCreate(m_world);
    dMass odeMass;
    dMassSetZero(&odeMass);
    const Vec3& inertia = mass.principalInertia;
    dMassSetParameters(&odeMass, mass.mass, 0, 0, 0, inertia.x(), inertia.y(), inertia.z(), 0, 0, 0);
    dBodySetMass(body->body, &odeMass);
    dBodySetPosition(body->body, com.x(), com.y(), com.z());
    dBodySetQuaternion(body->body, q);
    dBodySetLinearVel(body->body, spec.linearVelocity.x(), spec.linearVelocity.y(), spec.linearVelocity.z());
    dBodySetAngularVel(body->body, spec.angularVelocity.x(), spec.angularVelocity.y(),
                       spec.angularVelocity.z());
    // The gyroscopic term as the scenario says (ODE's is implicit); no
    // damping, never disabled.
    dBodySetGyroscopicMode(body->body, m_worldSettings.gyroscopic ? 1 : 0);
    dBodySetAutoDisableFlag(body->body, 0);
    dBodySetDamping(body->body, 0, 0);
    dGeomSetBody(body->geom, body->body);
  } else if (spec.motion == harness::Motion::Kinematic) {
    // ODE's kinematic body: infinite mass to joints, moved by its velocity
    // each step (set in ApplyLoads; here the start's).
    body->body = dBodyCreate(m_world);
    dBodySetKinematic(body->body);
    dBodySetPosition(body->body, com.x(), com.y(), com.z());
    dBodySetQuaternion(body->body, q);
    const Vec3 v = spec.linearVelocity + spec.angularVelocity.cross(com - spec.position);
    dBodySetLinearVel(body->body, v.x(), v.y(), v.z());
    dBodySetAngularVel(body->body, spec.angularVelocity.x(), spec.angularVelocity.y(),
                       spec.angularVelocity.z());
    dBodySetAutoDisableFlag(body->body, 0);
    dGeomSetBody(body->geom, body->body);
  } else {
    dGeomSetPosition(body->geom, com.x(), com.y(), com.z());
    dGeomSetQuaternion(body->geom, q);
  }
  m_bodies.push_back(std::move(body));
  return true;
}

Result<std::unique_ptr<harness::Backend>> OdeBackend::Create(const Run& run, OdeConfig config) {
  const OdeLibrary& library = OdeLibrary::Get();
  if (!library.DoublePrecision()) {
    return Error{"ode: the installed ODE is not the double-precision build (" + library.Configuration() +
                 ")"};
  }
  std::vector<BodyMass> masses;
  for (const BodySpec& spec : run.scenario.bodies) {
    auto mass = ComputeBodyMass(spec);
    if (!mass) return Error{"ode: " + mass.GetError().message};
    masses.push_back(mass.Value());
  }
  std::unique_ptr<OdeBackend> backend(new OdeBackend());
  backend->m_config = config;
  backend->m_runId = run.id;
  backend->m_timeStep = run.timeStep;
  backend->m_worldSettings = run.scenario.world;
  backend->m_world = dWorldCreate();
  // ODE's hash space with its default cell levels (2^-3 to 2^10 m, set
  // explicitly so the record does not depend on a library default).
  if (config.tuning == OdeTuning::Tuned) {
    backend->m_space = dHashSpaceCreate(nullptr);
    dHashSpaceSetLevels(backend->m_space, kOdeHashMinLevel, kOdeHashMaxLevel);
  } else {
    backend->m_space = dSimpleSpaceCreate(nullptr);
  }
  backend->m_contactGroup = dJointGroupCreate(0);
  const Vec3& g = run.scenario.world.gravity;
  dWorldSetGravity(backend->m_world, g.x(), g.y(), g.z());
  dWorldSetERP(backend->m_world, kOdeErp);
  dWorldSetCFM(backend->m_world, kOdeCfm);
  // The tuned quickstep keeps contacts alive with ODE's documented anti-jitter
  // layer; dWorldStep keeps ODE's 0 (kOdeTunedQuickStepSurfaceLayer says why).
  if (config.tuning == OdeTuning::Tuned && config.stepper == Stepper::QuickStep) {
    dWorldSetContactSurfaceLayer(backend->m_world, kOdeTunedQuickStepSurfaceLayer);
  }
  dWorldSetQuickStepNumIterations(backend->m_world,
                                  run.iterations > 0 ? run.iterations : kOdeDefaultQuickStepIterations);
  backend->m_specs = run.scenario.bodies;  // kept: Body::spec points into it
  for (size_t i = 0; i < run.scenario.bodies.size(); ++i) {
    // The destructor frees a partly built world, so a failure leaks nothing.
    auto added = backend->AddBody(backend->m_specs[i], masses[i], static_cast<int>(i));
    if (!added) return added.GetError();
  }
  backend->m_loads = run.scenario.loads;
  backend->m_impulses = run.scenario.impulses;
  backend->AddSettings(run);
  return std::unique_ptr<harness::Backend>(std::move(backend));
}

OdeBackend::~OdeBackend() {
  if (m_contactGroup != nullptr) dJointGroupDestroy(m_contactGroup);
  if (m_space != nullptr) dSpaceDestroy(m_space);  // destroys its geoms
  if (m_world != nullptr) dWorldDestroy(m_world);  // destroys its bodies
}

void OdeBackend::NearCallback(void* data, dGeomID geom1, dGeomID geom2) {
  const auto* a = static_cast<const Body*>(dGeomGetData(geom1));
  const auto* b = static_cast<const Body*>(dGeomGetData(geom2));
  // Static and kinematic bodies move nothing they touch among themselves.
  if (!a->dynamic && !b->dynamic) return;
  static_cast<OdeBackend*>(data)->m_pairs.emplace_back(a->index, b->index);
}

// The tangential part of the velocity of A relative to B at the contact
// point, normalised; false when it is below kOdeSlipSpeedFloor (no slip
// direction to align with: ODE's own tangent axes are kept).
bool OdeBackend::SlipDirection(const Body& a, const Body& b, const dContactGeom& contact,
                               dVector3 direction) const {
  dVector3 va = {0, 0, 0, 0};
  dVector3 vb = {0, 0, 0, 0};
  if (a.body != nullptr) dBodyGetPointVel(a.body, contact.pos[0], contact.pos[1], contact.pos[2], va);
  if (b.body != nullptr) dBodyGetPointVel(b.body, contact.pos[0], contact.pos[1], contact.pos[2], vb);
  const Vec3 normal(contact.normal[0], contact.normal[1], contact.normal[2]);
  Vec3 slip(va[0] - vb[0], va[1] - vb[1], va[2] - vb[2]);
  slip -= slip.dot(normal) * normal;
  const double speed = slip.norm();
  if (speed <= kOdeSlipSpeedFloor) return false;
  slip /= speed;
  direction[0] = slip.x();
  direction[1] = slip.y();
  direction[2] = slip.z();
  direction[3] = 0;
  return true;
}

// Why ODE must not be stepped with a contact its collider returned: a
// normal that is not a unit vector (dCollideConvexConvex returns (0, 0, 0)
// for hull faces that touch exactly, e.g. the blocks of an arch: its
// Jacobian row is then zero, the solver divides by its zero diagonal and
// the body's quaternion turns NaN, which dxNormalize4 aborts on; see
// docs/testbed-backends.md) or a non-finite point or depth. Empty when the
// contact is sound. Dropping such a contact instead would silently change
// the physics; the run stops with the reason.
static std::string UnsoundContact(const std::string& nameA, const std::string& nameB,
                                  const dContactGeom& contact) {
  const Vec3 normal(contact.normal[0], contact.normal[1], contact.normal[2]);
  const Vec3 point(contact.pos[0], contact.pos[1], contact.pos[2]);
  // ODE normalises its normals to round-off; a real normal is within 1e-6.
  constexpr double kUnitNormalTolerance = 1e-6;
  if (normal.allFinite() && std::abs(normal.norm() - 1.0) <= kUnitNormalTolerance && point.allFinite() &&
      std::isfinite(contact.depth)) {
    return {};
  }
  std::ostringstream problem;
  problem << "ODE's collider returned a contact between \"" << nameA << "\" and \"" << nameB
          << "\" with normal (" << normal.x() << ", " << normal.y() << ", " << normal.z() << "), point ("
          << point.x() << ", " << point.y() << ", " << point.z() << "), depth " << contact.depth
          << " m; not stepped (the solver would divide by its zero row and ODE abort)";
  return problem.str();
}

std::string OdeBackend::Collide(const Body& a, const Body& b) {
  dContact contacts[kOdeMaxContactsPerPair];
  std::memset(contacts, 0, sizeof(contacts));
  const int count = dCollide(a.geom, b.geom, kOdeMaxContactsPerPair, &contacts[0].geom, sizeof(dContact));
  for (int i = 0; i < count; ++i) {
    if (std::string problem = UnsoundContact(a.name, b.name, contacts[i].geom); !problem.empty())
      return problem;
  }
  const double friction = harness::Combine(m_worldSettings.frictionCombine, a.friction, b.friction);
  const double restitution =
      harness::Combine(m_worldSettings.restitutionCombine, a.restitution, b.restitution);
  for (int i = 0; i < count; ++i) {
    dContact& contact = contacts[i];
    contact.surface.mode = dContactApprox1;
    contact.surface.mu = friction;
    if (m_config.tuning == OdeTuning::Tuned && SlipDirection(a, b, contact.geom, contact.fdir1)) {
      contact.surface.mode |= dContactFDir1;
    }
    if (restitution > 0.0) {
      contact.surface.mode |= dContactBounce;
      contact.surface.bounce = restitution;
      contact.surface.bounce_vel = kOdeBounceVelocity;
    }
    const dJointID joint = dJointCreateContact(m_world, m_contactGroup, &contact);
    dJointAttach(joint, a.body, b.body);
    // ODE's normal points into geom1, i.e. from B = geom2 towards A = geom1.
    const dContactGeom& g = contact.geom;
    m_contacts.push_back({a.index, b.index, Vec3(g.pos[0], g.pos[1], g.pos[2]),
                          Vec3(g.normal[0], g.normal[1], g.normal[2]), g.depth});
  }
  return {};
}

// The first dynamic body whose state ODE must not be stepped with: a
// non-finite value, or a position beyond kMaxLength (the bound Talus's
// World refuses at too), where ODE's collision arithmetic overflows into
// the NaN quaternions its internal assertions abort on. Empty when none.
std::string OdeBackend::UnsafeState() const {
  for (const auto& body : m_bodies) {
    if (body->body == nullptr) continue;
    const dReal* p = dBodyGetPosition(body->body);
    const dReal* q = dBodyGetQuaternion(body->body);
    const dReal* v = dBodyGetLinearVel(body->body);
    const dReal* w = dBodyGetAngularVel(body->body);
    bool finite = true;
    for (int i = 0; i < 4; ++i) finite = finite && std::isfinite(q[i]);
    for (int i = 0; i < 3; ++i)
      finite = finite && std::isfinite(p[i]) && std::isfinite(v[i]) && std::isfinite(w[i]);
    if (!finite) return "body \"" + body->name + "\" has a non-finite state; not stepped (ODE would abort)";
    if (Vec3(p[0], p[1], p[2]).cwiseAbs().maxCoeff() > harness::kMaxLength) {
      return "body \"" + body->name + "\" is beyond " + SettingNumber(harness::kMaxLength) +
             " m from the origin; not stepped (ODE's collision arithmetic overflows there)";
    }
    // dHashSpace (tuned) numbers its cells with ints: a coordinate past
    // INT_MAX cells of its finest level aborts on an internal assertion
    // (collision_space.cpp, "aabbBound < dMaxIntExact"; found by the soak
    // suite: a box at 1e6 m/s). Half that reach leaves room for the AABB.
    const double hashReach =
        0.5 * static_cast<double>(std::numeric_limits<int>::max()) * std::ldexp(1.0, kOdeHashMinLevel);
    if (dSpaceGetClass(m_space) == dHashSpaceClass &&
        Vec3(p[0], p[1], p[2]).cwiseAbs().maxCoeff() > hashReach) {
      return "body \"" + body->name + "\" is beyond " + SettingNumber(hashReach) +
             " m from the origin; not stepped (dHashSpace numbers its cells with ints and aborts there)";
    }
  }
  return {};
}

void OdeBackend::Step() {
  m_contacts.clear();
  m_pairs.clear();
  m_failure = UnsafeState();
  if (!m_failure.empty()) return;
  tCurrentRun = &m_runId;
  tLastMessage.clear();
  // The pairs in the space's own order, geom 1 first (see the file comment).
  dSpaceCollide(m_space, this, &OdeBackend::NearCallback);
  for (const auto& [first, second] : m_pairs) {
    m_failure = Collide(*m_bodies[static_cast<size_t>(first)], *m_bodies[static_cast<size_t>(second)]);
    if (!m_failure.empty()) {
      dJointGroupEmpty(m_contactGroup);
      m_contacts.clear();
      tCurrentRun = nullptr;
      return;
    }
  }
  ApplyLoads();
  dRandSetSeed(m_randomSeed);
  // 0 when ODE could not take the step (it could not allocate its step
  // memory: a dense contact cluster asks for m^2 LCP entries).
  const int stepped = m_config.stepper == Stepper::Step ? dWorldStep(m_world, m_timeStep)
                                                        : dWorldQuickStep(m_world, m_timeStep);
  m_randomSeed = dRandGetSeed();
  ++m_stepIndex;
  const std::size_t joints = m_contacts.size();
  dJointGroupEmpty(m_contactGroup);
  tCurrentRun = nullptr;
  if (stepped == 0) {
    m_failure = std::string(m_config.stepper == Stepper::Step ? "dWorldStep" : "dWorldQuickStep") +
                " failed (ODE could not allocate its step memory; " + std::to_string(m_bodies.size()) +
                " bodies, " + std::to_string(joints) + " contact joints)" +
                (tLastMessage.empty() ? "" : "; last " + tLastMessage);
  }
}

// The step's loads as an ODE user adds them: dBodyAddForceAtPos (at a
// point) or dBodyAddForce and dBodyAddTorque, each load's share of the step,
// world axes; an impulse due now as the force that gives it over the step
// (dWorldImpulseToForce). ODE clears the forces after the step. A
// kinematic body's velocity is set again each step, so a body turning about
// an origin off its centre of mass keeps to its prescribed path.
void OdeBackend::ApplyLoads() {
  const double t = static_cast<double>(m_stepIndex) * m_timeStep;
  for (const auto& body : m_bodies) {
    if (body->body == nullptr || body->dynamic) continue;
    const dReal* p = dBodyGetPosition(body->body);
    const Vec3 origin = harness::KinematicPoseAt(*body->spec, t).origin;
    const Vec3 v =
        body->spec->linearVelocity + body->spec->angularVelocity.cross(Vec3(p[0], p[1], p[2]) - origin);
    dBodySetLinearVel(body->body, v.x(), v.y(), v.z());
  }
  for (const harness::AppliedImpulse& impulse : m_impulses) {
    if (!harness::AppliedImpulseAtStep(impulse, m_stepIndex, m_timeStep)) continue;
    const harness::BodyReading state = GetBodyState(impulse.body);
    dVector3 force;
    dWorldImpulseToForce(m_world, m_timeStep, impulse.linear.x(), impulse.linear.y(), impulse.linear.z(),
                         force);
    const dBodyID id = m_bodies[static_cast<size_t>(impulse.body)]->body;
    if (const auto point = harness::ImpulseWorldPoint(impulse, state.origin, state.orientation)) {
      dBodyAddForceAtPos(id, force[0], force[1], force[2], point->x(), point->y(), point->z());
    } else {
      dBodyAddForce(id, force[0], force[1], force[2]);
    }
  }
  for (const harness::AppliedLoad& load : m_loads) {
    const double share = harness::AppliedLoadShare(load, t, m_timeStep);
    if (share == 0.0) continue;
    const harness::BodyReading state = GetBodyState(load.body);
    const harness::WorldLoad world = harness::ToWorldLoad(load, share, state.origin, state.orientation);
    const dBodyID id = m_bodies[static_cast<size_t>(load.body)]->body;
    const Vec3& f = world.force;
    if (world.point) {
      dBodyAddForceAtPos(id, f.x(), f.y(), f.z(), world.point->x(), world.point->y(), world.point->z());
    } else {
      dBodyAddForce(id, f.x(), f.y(), f.z());
    }
    dBodyAddTorque(id, world.torque.x(), world.torque.y(), world.torque.z());
  }
}

harness::BodyReading OdeBackend::GetBodyState(int index) const {
  const Body& body = *m_bodies.at(static_cast<size_t>(index));
  harness::BodyReading state;
  const dReal* position = dGeomGetPosition(body.geom);
  dQuaternion q;
  dGeomGetQuaternion(body.geom, q);
  state.centerOfMass = Vec3(position[0], position[1], position[2]);
  state.orientation = (Quat(q[0], q[1], q[2], q[3]) * body.mass.principalRotation.conjugate()).normalized();
  const Mat3 rotation = state.orientation.toRotationMatrix();
  state.origin = state.centerOfMass - rotation * body.mass.centroid;
  if (body.body != nullptr) {
    // A kinematic body's mass data stay zero (infinite mass).
    const dReal* v = dBodyGetLinearVel(body.body);
    const dReal* w = dBodyGetAngularVel(body.body);
    state.linearVelocity = Vec3(v[0], v[1], v[2]);
    state.angularVelocity = Vec3(w[0], w[1], w[2]);
    state.mass = body.mass.mass;
    state.worldInertia = rotation * body.mass.inertia * rotation.transpose();
  }
  return state;
}

void OdeBackend::AddSettings(const Run& run) {
  const bool quick = m_config.stepper == Stepper::QuickStep;
  const bool tuned = m_config.tuning == OdeTuning::Tuned;
  m_settings = {
      {"configuration", tuned ? "tuned (ODE's documented practice for Coulomb friction and many bodies)"
                              : "defaults (what a new ODE user gets)"},
      {"engine", "ODE " + std::string(OdeLibrary::Get().Configuration())},
      {"precision", "double (dDOUBLE, checked with dCheckConfiguration)"},
      {"stepper",
       quick ? "dWorldQuickStep (iterative SOR / projected Gauss-Seidel)" : "dWorldStep (Dantzig LCP)"},
      {"time step (s)", SettingNumber(run.timeStep)},
      {"integrator", "semi-implicit (symplectic) Euler: v += h a, then x += h v"},
      {"solver iterations", quick ? std::to_string(dWorldGetQuickStepNumIterations(m_world)) +
                                        (run.iterations > 0 ? "" : " (engine default)")
                                  : std::string("n/a (direct LCP solve)")},
      {"quickstep SOR w", SettingNumber(dWorldGetQuickStepW(m_world))},
      {"random seed", "0 per world (quickstep's constraint order; the generator is swapped per world)"},
      {"erp", SettingNumber(dWorldGetERP(m_world))},
      {"cfm", SettingNumber(dWorldGetCFM(m_world))},
      tuned && quick
          ? Setting{"contact surface layer (m)", SettingNumber(dWorldGetContactSurfaceLayer(m_world)), "0",
                    kOdeSurfaceLayerEffect}
          : Setting{"contact surface layer (m)", SettingNumber(dWorldGetContactSurfaceLayer(m_world))},
      {"contact max correcting velocity (m/s)", SettingNumber(dWorldGetContactMaxCorrectingVel(m_world))},
      {"max contacts per pair", std::to_string(kOdeMaxContactsPerPair)},
      {"friction model", "dContactApprox1: mu scales the normal force (a pyramid: two tangent rows)",
       "dContactApprox0: mu is a force bound in newtons",
       "needed to pose the scenario's Coulomb coefficient at all: with a bound in newtons the stop "
       "distance of a sliding box would depend on its mass"},
      tuned ? Setting{"friction directions",
                      "dContactFDir1 along the slip (tangential relative velocity at the contact) when it "
                      "exceeds " +
                          SettingNumber(kOdeSlipSpeedFloor, 3) + " m/s",
                      "ODE's own tangent axes (dPlaneSpace of the normal: world x and z on a floor)",
                      kOdeFdir1Effect}
            : Setting{"friction directions", "ODE's own tangent axes (dPlaneSpace of the normal)"},
      {"friction combine", harness::CombineRuleName(run.scenario.world.frictionCombine)},
      {"restitution combine", harness::CombineRuleName(run.scenario.world.restitutionCombine)},
      {"bounce velocity threshold (m/s)", SettingNumber(kOdeBounceVelocity),
       "no bounce (dContactBounce is per contact and off unless asked)",
       "poses the scenario's restitution; 0.2 m/s, Bullet's default threshold, keeps resting bodies from "
       "bouncing on the g h they gain each step"},
      tuned ? Setting{"space",
                      "dHashSpace, levels " + std::to_string(kOdeHashMinLevel) + " to " +
                          std::to_string(kOdeHashMaxLevel) + "; pairs in the space's own order",
                      "dSimpleSpace (every pair tested)", kOdeHashSpaceEffect}
            : Setting{"space", "dSimpleSpace (every pair tested, in the space's own order)"},
      run.scenario.world.gyroscopic
          ? Setting{"gyroscopic term", "on (dBodySetGyroscopicMode 1, implicit)"}
          : Setting{"gyroscopic term", "off (dBodySetGyroscopicMode 0)", "on (implicit)",
                    "the scenario asks for no gyroscopic term (angular velocity exactly constant)"},
      {"damping", "linear 0, angular 0"},
      {"auto disable", "off"},
      {"hull shapes", "dConvex from the qhull hull, one polygon per face, centred on the centroid"},
      {"mass properties", "from talus::reference::ComputeBodyMass (exact), principal axes"},
  };
  // Listed only where the scenario uses them, so other runs' records stay as they were.
  if (!run.scenario.loads.empty() || !run.scenario.impulses.empty()) {
    m_settings.push_back(
        {"loads and impulses",
         "dBodyAddForceAtPos (at a point) or dBodyAddForce and dBodyAddTorque before each "
         "step, scaled by the step's share of the window; an impulse as dWorldImpulseToForce's "
         "force over its step"});
  }
  for (const BodySpec& spec : run.scenario.bodies) {
    if (spec.motion != harness::Motion::Kinematic) continue;
    m_settings.push_back({"kinematic bodies",
                          "dBodySetKinematic with the prescribed velocities (set each step): infinite mass "
                          "to the contact joints, moved by ODE"});
    break;
  }
}

}  // namespace

void RegisterOdeBackends(harness::BackendRegistry& registry) {
  // ODE keeps library-wide state and per-thread collision data.
  const harness::ThreadSafety ode = harness::ThreadSafety::SharesStateOf("ode");
  for (const OdeTuning tuning : {OdeTuning::Defaults, OdeTuning::Tuned}) {
    const bool tuned = tuning == OdeTuning::Tuned;
    const std::string configuration =
        tuned ? " (tuned: friction direction along the slip, dHashSpace)" : " (ODE's defaults)";
    registry.Register(BackendName({Stepper::Step, tuning}),
                      "ODE (double): dWorldStep, global LCP by Dantzig" + configuration, ode,
                      [tuning](const Run& run) {
                        return OdeBackend::Create(run, {Stepper::Step, tuning});
                      });
    registry.Register(BackendName({Stepper::QuickStep, tuning}),
                      "ODE (double): dWorldQuickStep, iterative SOR" + configuration, ode,
                      [tuning](const Run& run) {
                        return OdeBackend::Create(run, {Stepper::QuickStep, tuning});
                      });
  }
}

}  // namespace talus::reference
