// The soft step: rows, colouring, the sub-step chain and the per-pair
// passes. The step, the separation update and the derivation of the soft
// rows are in dynamics/soft_step_solver.h.
#include "dynamics/soft_step_solver.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>

#include "dynamics/contact_row_set.h"
#include "dynamics/integrator.h"

namespace talus {
namespace {

// Bodies per chunk of the integration phases (as World::Step's kBodyGrain:
// a body's update is 50-300 ns, a chunk tens of microseconds).
constexpr int kIntegrationBodyGrain = 128;
// Pairs per chunk of a colour's pass: one soft pair's solve is a few hundred
// nanoseconds, so a chunk is several microseconds, above the cost of
// claiming it. Boundaries depend on the pair count only.
constexpr int kColourPairGrain = 16;
// Pairs per chunk of Prepare's parallel pass (a few microseconds each).
constexpr int kPreparePairGrain = 32;

Vec3 RelativeVelocity(const BodySim& a, const Vec3& rA, const BodySim& b, const Vec3& rB) {
  return (a.linearVelocity + a.angularVelocity.cross(rA)) - (b.linearVelocity + b.angularVelocity.cross(rB));
}

// The velocities of one body as a pass works on them: a local copy, written
// back only when the rows may move the body.
struct PassBody {
  Vec3 v;
  Vec3 w;
};

// Row speed Cdot = d.(vA - vB) + (rA x d).wA - (rB x d).wB.
// Forced inline: called per row per pass, and GCC left the calls in
// (7% of a pyramid step in the calls alone, perf).
[[gnu::always_inline]] inline double RowSpeed(const Vec3& d, const RowJacobian& j, const PassBody& a,
                                              const PassBody& b) {
  return d.dot(a.v - b.v) + j.angularA.dot(a.w) - j.angularB.dot(b.w);
}

[[gnu::always_inline]] inline void ApplyRow(const Vec3& d, const RowJacobian& j, double impulse,
                                            const SoftPair& pair, PassBody& a, PassBody& b) {
  a.v += (pair.invMassA * impulse) * d;
  a.w += impulse * j.imageA;
  b.v -= (pair.invMassB * impulse) * d;
  b.w -= impulse * j.imageB;
}

// The velocity half of the integrator for one sub-step: as
// IntegrateVelocities (dynamics/integrator.h) but the accumulated forces are
// kept, since every sub-step applies them; the step clears them at its end.
int IntegrateSubstepVelocities(std::span<BodySim> bodies, const Vec3& gravity, double h) {
  int integrated = 0;
  for (BodySim& body : bodies) {
    if (body.type != BodyType::Dynamic || !body.awake) continue;
    body.startLinearVelocity = body.linearVelocity;
    body.linearVelocity += h * (gravity + body.invMass * body.force);
    body.freeLinearVelocity = body.linearVelocity;
    body.angularVelocity += h * (body.invInertiaWorld * body.torque);
    ++integrated;
  }
  return integrated;
}

}  // namespace

Softness MakeSoftness(double hertz, double dampingRatio, double h) {
  const double omega = 2.0 * std::numbers::pi * hertz;
  const double a1 = 2.0 * dampingRatio + h * omega;
  const double a2 = h * omega * a1;
  const double a3 = 1.0 / (1.0 + a2);
  return {.biasRate = omega / a1, .massScale = a2 * a3, .impulseScale = a3};
}

std::string ValidateSoftStepSettings(const WorldSettings& settings) {
  const SoftStepSettings& s = settings.methods.softStep;
  if (settings.methods.stepSolver != StepSolver::SequentialImpulses &&
      settings.methods.stepSolver != StepSolver::SoftStep) {
    return "WorldSettings.methods.stepSolver = " +
           std::to_string(static_cast<int>(settings.methods.stepSolver)) + " is not a StepSolver";
  }
  if (s.substeps < 1 || s.substeps > 1000) {
    return "WorldSettings.methods.softStep.substeps = " + std::to_string(s.substeps) +
           " is outside [1, 1000]";
  }
  if (!std::isfinite(s.contactHertz) || !(s.contactHertz > 0.0)) {
    return "WorldSettings.methods.softStep.contactHertz = " + std::to_string(s.contactHertz) +
           " Hz must be finite and > 0";
  }
  if (!std::isfinite(s.dampingRatio) || s.dampingRatio < 0.0) {
    return "WorldSettings.methods.softStep.dampingRatio = " + std::to_string(s.dampingRatio) +
           " must be finite and >= 0";
  }
  if (!std::isfinite(s.pushOutSpeed) || !(s.pushOutSpeed > 0.0)) {
    return "WorldSettings.methods.softStep.pushOutSpeed = " + std::to_string(s.pushOutSpeed) +
           " m/s must be finite and > 0";
  }
  return {};
}

// Two passes, as the Sequential Impulses Prepare: a serial one decides
// which contacts get rows and gives each pair its points' places; the
// second fills each pair's rows in its own places on the runner's threads.
void SoftStepSolver::Prepare(std::span<const BodySim> bodies, std::span<const Contact> contacts,
                             const WorldSettings& settings, double dt, StepStatistics& stats) {
  const SoftStepSettings& soft = settings.methods.softStep;
  m_substeps = soft.substeps;
  m_h = dt / soft.substeps;
  m_pushOutSpeed = soft.pushOutSpeed;
  m_restitutionThreshold = settings.restitutionThreshold;
  const double hertz = std::min(soft.contactHertz, 0.25 / m_h);
  const Softness contactSoftness = MakeSoftness(hertz, soft.dampingRatio, m_h);
  const Softness staticSoftness = MakeSoftness(2.0 * hertz, soft.dampingRatio, m_h);

  m_pairs.clear();
  int points = 0;
  int blocks = 0;
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const Contact& contact = contacts[c];
    const BodySim& a = bodies[static_cast<std::size_t>(contact.bodyA)];
    const BodySim& b = bodies[static_cast<std::size_t>(contact.bodyB)];
    if ((!a.IsSolverDynamic() && !b.IsSolverDynamic()) || contact.manifold.pointCount == 0) continue;
    SoftPair pair;
    pair.contact = static_cast<int>(c);
    pair.bodyA = contact.bodyA;
    pair.bodyB = contact.bodyB;
    pair.firstPoint = points;
    pair.pointCount = contact.manifold.pointCount;
    pair.movesA = a.IsSolverDynamic();
    pair.movesB = b.IsSolverDynamic();
    pair.softness = pair.movesA && pair.movesB ? contactSoftness : staticSoftness;
    points += pair.pointCount;
    stats.contactPoints += pair.pointCount;
    if (contact.friction > 0.0) {
      stats.frictionRows += 2 * pair.pointCount;
    } else {
      stats.frictionRowsSkipped += 2 * pair.pointCount;
    }
    if (contact.restitution == 0.0) stats.restitutionSkipped += pair.pointCount;
    if (pair.pointCount >= 2 && pair.pointCount <= 4) pair.block = blocks++;
    m_pairs.push_back(pair);
  }
  m_points.resize(static_cast<std::size_t>(points));
  m_blockInverses.resize(static_cast<std::size_t>(blocks));
  const JobPhase phase{.count = static_cast<int>(m_pairs.size()), .grain = kPreparePairGrain};
  RunPhasesWith(m_runner, std::span<const JobPhase>(&phase, 1), [&](int, int begin, int end) {
    for (int p = begin; p < end; ++p) {
      SoftPair& pair = m_pairs[static_cast<std::size_t>(p)];
      PreparePair(bodies, contacts[static_cast<std::size_t>(pair.contact)], settings, pair);
    }
  });
  Colour(static_cast<int>(bodies.size()));
  stats.solverColours = ColourCount();
  stats.overflowPairs = OverflowCount();
  stats.velocitySweeps = 2 * m_substeps;  // one soft solve and one relax per sub-step
}

void SoftStepSolver::PreparePair(std::span<const BodySim> bodies, const Contact& contact,
                                 const WorldSettings& settings, SoftPair& pair) {
  const BodySim& a = bodies[static_cast<std::size_t>(pair.bodyA)];
  const BodySim& b = bodies[static_cast<std::size_t>(pair.bodyB)];
  // Bodies the rows may not move get zero inverse mass and inertia, so a row
  // applies exactly zero to them without a branch.
  const Mat3 invInertiaA = pair.movesA ? a.invInertiaWorld : Mat3::Zero();
  const Mat3 invInertiaB = pair.movesB ? b.invInertiaWorld : Mat3::Zero();
  pair.invMassA = pair.movesA ? a.invMass : 0.0;
  pair.invMassB = pair.movesB ? b.invMass : 0.0;
  pair.normal = contact.manifold.normal;
  pair.friction = contact.friction;
  pair.restitution = contact.restitution;
  pair.startCenterA = a.center;
  pair.startCenterB = b.center;
  const Vec3& n = pair.normal;
  // Friction basis: t1 along the mean sliding velocity when there is one.
  Vec3 slide = Vec3::Zero();
  for (int i = 0; i < pair.pointCount; ++i) {
    const Vec3& p = contact.manifold.points[static_cast<std::size_t>(i)].position;
    slide += RelativeVelocity(a, p - a.center, b, p - b.center);
  }
  slide -= n * n.dot(slide);
  const double speed = slide.norm() / pair.pointCount;
  pair.tangent[0] = speed > kSlidingSpeed ? Vec3(slide.normalized()) : AnyPerpendicular(n);
  pair.tangent[1] = n.cross(pair.tangent[0]);
  // Impulses are stored per step (StoreImpulses); a sub-step carries its share.
  const double share = settings.methods.warmStarting ? 1.0 / m_substeps : 0.0;
  for (int i = 0; i < pair.pointCount; ++i) {
    const std::size_t pi = static_cast<std::size_t>(i);
    const ContactPoint& cp = contact.manifold.points[pi];
    SoftPoint& point = m_points[static_cast<std::size_t>(pair.firstPoint + i)];
    point = SoftPoint{};
    point.armA = cp.position - a.center;
    point.armB = cp.position - b.center;
    point.localAnchorA = a.orientation.conjugate() * point.armA;
    point.localAnchorB = b.orientation.conjugate() * point.armB;
    point.depth = cp.depth;
    point.normal = MakeRowJacobian(n, point.armA, point.armB, invInertiaA, invInertiaB);
    point.normalMass = RowEffectiveMass(point.normal, pair.invMassA, pair.invMassB);
    point.approachSpeed = n.dot(RelativeVelocity(a, point.armA, b, point.armB));
    point.normalImpulse = share * contact.normalImpulse[pi];
    for (int k = 0; k < 2; ++k) {
      point.tangent[k] = MakeRowJacobian(pair.tangent[k], point.armA, point.armB, invInertiaA, invInertiaB);
      point.tangentMass[k] = RowEffectiveMass(point.tangent[k], pair.invMassA, pair.invMassB);
      point.tangentImpulse[k] =
          pair.friction > 0.0 ? share * contact.frictionImpulse[pi].dot(pair.tangent[k]) : 0.0;
    }
  }
  if (pair.block >= 0) PrepareBlock(pair);
}

// K+ of the pair's normal rows (dynamics/normal_block.h), zero rows and
// columns past the pair's points.
void SoftStepSolver::PrepareBlock(const SoftPair& pair) {
  const int count = pair.pointCount;
  const SoftPoint* points = &m_points[static_cast<std::size_t>(pair.firstPoint)];
  const auto jacobian = [points](int i) -> const RowJacobian& { return points[i].normal; };
  // The same block and pseudo-inverse as the Sequential Impulses rows'.
  const Eigen::Matrix4d k = NormalBlock(count, pair.invMassA, pair.invMassB, jacobian);
  m_blockInverses[static_cast<std::size_t>(pair.block)] =
      BlockPseudoInverse(k, count, NormalArmsOf(count, jacobian));
}

// Greedy first fit in pair order (ColourPairs), then the pairs listed
// colour by colour in pair order: a function of the contacts alone.
void SoftStepSolver::Colour(int bodyCount) {
  m_inputs.clear();
  for (const SoftPair& pair : m_pairs) {
    m_inputs.push_back(
        {.bodyA = pair.bodyA, .bodyB = pair.bodyB, .movesA = pair.movesA, .movesB = pair.movesB});
  }
  ColourPairs(m_inputs, bodyCount, m_colourOf, m_used);
  int used = 0;
  std::vector<int>& start = m_colourStart;
  start.assign(static_cast<std::size_t>(kColourCount) + 1, 0);
  m_overflow.clear();
  for (std::size_t p = 0; p < m_pairs.size(); ++p) {
    const int colour = m_colourOf[p];
    if (colour == kOverflowColour) {
      m_overflow.push_back(static_cast<int>(p));
    } else {
      ++start[static_cast<std::size_t>(colour) + 1];
      used = std::max(used, colour + 1);
    }
  }
  start.resize(static_cast<std::size_t>(used) + 1);
  for (int c = 0; c < used; ++c) start[static_cast<std::size_t>(c) + 1] += start[static_cast<std::size_t>(c)];
  m_colourPairs.resize(static_cast<std::size_t>(start.back()));
  // Fill each colour's slots in pair order (a running cursor per colour).
  m_used.assign(static_cast<std::size_t>(used), 0u);
  for (std::size_t p = 0; p < m_pairs.size(); ++p) {
    const int colour = m_colourOf[p];
    if (colour == kOverflowColour) continue;
    const std::size_t c = static_cast<std::size_t>(colour);
    m_colourPairs[static_cast<std::size_t>(start[c]) + m_used[c]++] = static_cast<int>(p);
  }
}

void SoftStepSolver::AddPass(Pass pass) {
  for (int c = 0; c < ColourCount(); ++c) {
    const int count =
        m_colourStart[static_cast<std::size_t>(c) + 1] - m_colourStart[static_cast<std::size_t>(c)];
    m_jobs.push_back({.kind = PhaseJob::Kind::Colour, .pass = pass, .colour = c});
    m_phases.push_back({.count = count, .grain = kColourPairGrain});
  }
  m_jobs.push_back({.kind = PhaseJob::Kind::Overflow, .pass = pass});
  m_phases.push_back({.count = m_overflow.empty() ? 0 : 1, .grain = 1});
}

int SoftStepSolver::Step(std::span<BodySim> bodies, const WorldSettings& settings, double /*dt*/) {
  const int bodyCount = static_cast<int>(bodies.size());
  m_jobs.clear();
  m_phases.clear();
  for (int s = 0; s < m_substeps; ++s) {
    m_jobs.push_back({.kind = PhaseJob::Kind::IntegrateVelocities});
    m_phases.push_back({.count = bodyCount, .grain = kIntegrationBodyGrain});
    if (settings.methods.warmStarting || s > 0) AddPass(Pass::WarmStart);
    AddPass(Pass::Solve);
    m_jobs.push_back({.kind = PhaseJob::Kind::IntegratePositions});
    m_phases.push_back({.count = bodyCount, .grain = kIntegrationBodyGrain});
    AddPass(Pass::Relax);
  }
  AddPass(Pass::Restitution);
  m_jobs.push_back({.kind = PhaseJob::Kind::ClearForces});
  m_phases.push_back({.count = bodyCount, .grain = kIntegrationBodyGrain});

  // Dynamic bodies integrated, counted in the first sub-step (an integer sum,
  // the same in any order).
  std::atomic<int> integrated{0};
  const int firstPositions = [&] {
    for (std::size_t j = 0; j < m_jobs.size(); ++j) {
      if (m_jobs[j].kind == PhaseJob::Kind::IntegratePositions) return static_cast<int>(j);
    }
    return 0;
  }();
  RunPhasesWith(m_runner, m_phases, [&](int phase, int begin, int end) {
    const PhaseJob& job = m_jobs[static_cast<std::size_t>(phase)];
    const std::span<BodySim> chunk =
        job.kind == PhaseJob::Kind::Colour || job.kind == PhaseJob::Kind::Overflow
            ? std::span<BodySim>()
            : bodies.subspan(static_cast<std::size_t>(begin), static_cast<std::size_t>(end - begin));
    switch (job.kind) {
      case PhaseJob::Kind::IntegrateVelocities: {
        const int n = IntegrateSubstepVelocities(chunk, settings.gravity, m_h);
        if (phase < firstPositions) integrated.fetch_add(n, std::memory_order_relaxed);
        return;
      }
      case PhaseJob::Kind::IntegratePositions:
        IntegratePositions(chunk, m_h, false, settings.methods.rotation, settings.methods.translation);
        return;
      case PhaseJob::Kind::ClearForces:
        for (BodySim& body : chunk) {
          body.force.setZero();
          body.torque.setZero();
        }
        return;
      case PhaseJob::Kind::Colour: {
        const int first = m_colourStart[static_cast<std::size_t>(job.colour)];
        for (int i = begin; i < end; ++i) {
          RunPass(bodies, job.pass,
                  m_pairs[static_cast<std::size_t>(m_colourPairs[static_cast<std::size_t>(first + i)])]);
        }
        return;
      }
      case PhaseJob::Kind::Overflow:
        for (const int p : m_overflow) RunPass(bodies, job.pass, m_pairs[static_cast<std::size_t>(p)]);
        return;
    }
  });
  return integrated.load();
}

void SoftStepSolver::RunPass(std::span<BodySim> bodies, Pass pass, const SoftPair& pair) {
  switch (pass) {
    case Pass::WarmStart:
      WarmStartPair(bodies, pair);
      return;
    case Pass::Solve:
      SolvePair(bodies, pair, true);
      return;
    case Pass::Relax:
      SolvePair(bodies, pair, false);
      return;
    case Pass::Restitution:
      RestitutionPair(bodies, pair);
      return;
  }
}

namespace {

// The pair's two bodies' velocities as a pass reads them, and their write-back.
struct PairBodies {
  BodySim& a;
  BodySim& b;
  PassBody va;
  PassBody vb;
  PairBodies(std::span<BodySim> bodies, const SoftPair& pair)
      : a(bodies[static_cast<std::size_t>(pair.bodyA)]),
        b(bodies[static_cast<std::size_t>(pair.bodyB)]),
        va{a.linearVelocity, a.angularVelocity},
        vb{b.linearVelocity, b.angularVelocity} {}
  // Only a body the rows may move is written: an immovable one may be read
  // by pairs of the same colour on other threads at the same time.
  void Store(const SoftPair& pair) {
    if (pair.movesA) {
      a.linearVelocity = va.v;
      a.angularVelocity = va.w;
    }
    if (pair.movesB) {
      b.linearVelocity = vb.v;
      b.angularVelocity = vb.w;
    }
  }
};

}  // namespace

void SoftStepSolver::WarmStartPair(std::span<BodySim> bodies, const SoftPair& pair) {
  PairBodies body(bodies, pair);
  for (int i = 0; i < pair.pointCount; ++i) {
    const SoftPoint& point = m_points[static_cast<std::size_t>(pair.firstPoint + i)];
    ApplyRow(pair.normal, point.normal, point.normalImpulse, pair, body.va, body.vb);
    for (int k = 0; k < 2; ++k) {
      ApplyRow(pair.tangent[k], point.tangent[k], point.tangentImpulse[k], pair, body.va, body.vb);
    }
  }
  body.Store(pair);
}

void SoftStepSolver::SolvePair(std::span<BodySim> bodies, const SoftPair& pair, bool useBias) {
  PairBodies body(bodies, pair);
  const Vec3& n = pair.normal;
  // How far each body has moved since the step's start (header: separation).
  const Vec3 moved = (body.a.center - pair.startCenterA) - (body.b.center - pair.startCenterB);
  // The turns as matrices, once per pair: a point's arm is then 15
  // operations instead of a quaternion product's 30.
  const Mat3 turnA = body.a.orientation.toRotationMatrix();
  const Mat3 turnB = body.b.orientation.toRotationMatrix();
  const double invH = 1.0 / m_h;
  double gaps[kMaxManifoldPoints];
  bool touching = true;
  for (int i = 0; i < pair.pointCount; ++i) {
    const SoftPoint& point = m_points[static_cast<std::size_t>(pair.firstPoint + i)];
    const Vec3 turned = (turnA * point.localAnchorA - point.armA) - (turnB * point.localAnchorB - point.armB);
    gaps[i] = n.dot(moved + turned) - point.depth;
    touching = touching && gaps[i] <= 0.0;
  }
  const bool solved = pair.block >= 0 && touching &&
                      SolveBlock(pair, gaps, useBias, body.va.v, body.va.w, body.vb.v, body.vb.w);
  for (int i = 0; i < pair.pointCount && !solved; ++i) {
    SoftPoint& point = m_points[static_cast<std::size_t>(pair.firstPoint + i)];
    const double gap = gaps[i];
    double bias = 0.0;
    double massScale = 1.0;
    double impulseScale = 0.0;
    if (gap > 0.0) {
      bias = gap * invH;  // speculative: close the gap this sub-step, no further
    } else if (useBias) {
      bias = std::max(pair.softness.biasRate * gap, -m_pushOutSpeed);
      massScale = pair.softness.massScale;
      impulseScale = pair.softness.impulseScale;
    }
    const double speed = RowSpeed(n, point.normal, body.va, body.vb);
    const double change = -point.normalMass * massScale * (speed + bias) - impulseScale * point.normalImpulse;
    const double next = std::max(point.normalImpulse + change, 0.0);
    const double applied = next - point.normalImpulse;
    point.normalImpulse = next;
    point.maxNormalImpulse = std::max(point.maxNormalImpulse, next);
    ApplyRow(n, point.normal, applied, pair, body.va, body.vb);
  }
  if (pair.friction > 0.0) {
    for (int i = 0; i < pair.pointCount; ++i) {
      SoftPoint& point = m_points[static_cast<std::size_t>(pair.firstPoint + i)];
      const double bound = pair.friction * point.normalImpulse;
      for (int k = 0; k < 2; ++k) {
        const double speed = RowSpeed(pair.tangent[k], point.tangent[k], body.va, body.vb);
        const double next = std::clamp(point.tangentImpulse[k] - point.tangentMass[k] * speed, -bound, bound);
        const double applied = next - point.tangentImpulse[k];
        point.tangentImpulse[k] = next;
        ApplyRow(pair.tangent[k], point.tangent[k], applied, pair, body.va, body.vb);
      }
    }
  }
  body.Store(pair);
}

bool SoftStepSolver::SolveBlock(const SoftPair& pair, const double* gaps, bool useBias, Vec3& va, Vec3& wa,
                                Vec3& vb, Vec3& wb) {
  const Vec3& n = pair.normal;
  SoftPoint* points = &m_points[static_cast<std::size_t>(pair.firstPoint)];
  Eigen::Vector4d target = Eigen::Vector4d::Zero();
  Eigen::Vector4d impulse = Eigen::Vector4d::Zero();
  for (int i = 0; i < pair.pointCount; ++i) {
    const RowJacobian& j = points[i].normal;
    const double speed = n.dot(va - vb) + j.angularA.dot(wa) - j.angularB.dot(wb);
    const double bias = useBias ? std::max(pair.softness.biasRate * gaps[i], -m_pushOutSpeed) : 0.0;
    target[i] = speed + bias;
    impulse[i] = points[i].normalImpulse;
  }
  const double massScale = useBias ? pair.softness.massScale : 1.0;
  const double impulseScale = useBias ? pair.softness.impulseScale : 0.0;
  const Eigen::Vector4d change =
      -massScale * (m_blockInverses[static_cast<std::size_t>(pair.block)] * target) - impulseScale * impulse;
  for (int i = 0; i < pair.pointCount; ++i) {
    if (!(impulse[i] + change[i] >= 0.0)) return false;
  }
  for (int i = 0; i < pair.pointCount; ++i) {
    SoftPoint& point = points[i];
    point.normalImpulse = impulse[i] + change[i];
    point.maxNormalImpulse = std::max(point.maxNormalImpulse, point.normalImpulse);
    va += (pair.invMassA * change[i]) * n;
    wa += change[i] * point.normal.imageA;
    vb -= (pair.invMassB * change[i]) * n;
    wb -= change[i] * point.normal.imageB;
  }
  return true;
}

void SoftStepSolver::RestitutionPair(std::span<BodySim> bodies, const SoftPair& pair) {
  if (pair.restitution == 0.0) return;
  PairBodies body(bodies, pair);
  for (int i = 0; i < pair.pointCount; ++i) {
    SoftPoint& point = m_points[static_cast<std::size_t>(pair.firstPoint + i)];
    if (point.approachSpeed > -m_restitutionThreshold || point.maxNormalImpulse == 0.0) continue;
    const double speed = RowSpeed(pair.normal, point.normal, body.va, body.vb);
    const double change = -point.normalMass * (speed + pair.restitution * point.approachSpeed);
    const double next = std::max(point.normalImpulse + change, 0.0);
    const double applied = next - point.normalImpulse;
    point.normalImpulse = next;
    point.maxNormalImpulse = std::max(point.maxNormalImpulse, next);
    ApplyRow(pair.normal, point.normal, applied, pair, body.va, body.vb);
  }
  body.Store(pair);
}

void SoftStepSolver::StoreImpulses(std::span<Contact> contacts) const {
  const double steps = m_substeps;
  for (const SoftPair& pair : m_pairs) {
    Contact& contact = contacts[static_cast<std::size_t>(pair.contact)];
    for (int i = 0; i < pair.pointCount; ++i) {
      const SoftPoint& point = m_points[static_cast<std::size_t>(pair.firstPoint + i)];
      const std::size_t pi = static_cast<std::size_t>(i);
      contact.normalImpulse[pi] = steps * point.normalImpulse;
      contact.frictionImpulse[pi] =
          steps * (point.tangentImpulse[0] * pair.tangent[0] + point.tangentImpulse[1] * pair.tangent[1]);
    }
  }
}

}  // namespace talus
