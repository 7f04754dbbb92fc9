// Sequential Impulses on contact and friction rows: building the rows and
// the solver bodies (Prepare), warm start, split impulses and the impulses
// stored back. The constraint derivations
// and the data layout are in dynamics/contact_solver.h; the velocity sweeps
// in contact_solver_sweep.cpp.
#include "dynamics/contact_solver.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "dynamics/bounce_timing.h"

namespace talus {
namespace {

// Below this tangential speed (m/s) the friction basis is a fixed function
// of the normal instead of the sliding direction: a direction computed from
// round-off would only add noise.
constexpr double kSlidingSpeed = 1e-9;

// A unit vector orthogonal to the unit `n`, from the world axis least
// aligned with it (deterministic and well conditioned).
Vec3 AnyPerpendicular(const Vec3& n) {
  const Vec3 a = n.cwiseAbs();
  Vec3 axis = Vec3::UnitX();
  if (a.y() <= a.x() && a.y() <= a.z()) {
    axis = Vec3::UnitY();
  } else if (a.z() <= a.x() && a.z() <= a.y()) {
    axis = Vec3::UnitZ();
  }
  return n.cross(axis).normalized();
}

// Linear velocity at the step's start: the integrator records it for the
// bodies it accelerated (awake dynamic); every other body keeps its own.
const Vec3& StartVelocity(const BodySim& body) {
  return body.IsSolverDynamic() ? body.startLinearVelocity : body.linearVelocity;
}

// Velocity of A relative to B at the contact point (see header).
Vec3 RelativeVelocity(const Vec3& vA, const Vec3& wA, const Vec3& rA, const Vec3& vB, const Vec3& wB,
                      const Vec3& rB) {
  return (vA + wA.cross(rA)) - (vB + wB.cross(rB));
}

}  // namespace

RowJacobian ContactSolver::MakeJacobian(const Vec3& d, const Vec3& rA, const Vec3& rB,
                                        const Mat3& invInertiaA, const Mat3& invInertiaB) {
  RowJacobian j;
  j.angularA = rA.cross(d);
  j.angularB = rB.cross(d);
  j.imageA = invInertiaA * j.angularA;
  j.imageB = invInertiaB * j.angularB;
  return j;
}

double ContactSolver::RowMass(const RowJacobian& j, const PairRows& pair) {
  const double k = pair.invMassA + pair.invMassB + j.angularA.dot(j.imageA) + j.angularB.dot(j.imageB);
  return k > 0.0 ? 1.0 / k : 0.0;
}

// Whether a pair carries load now (shock propagation's levels): some point
// within one slop of touching, the band the solver treats as resting. A
// speculative pair whose points are further apart (a body that could reach
// the other within the step) supports nothing yet.
bool Touching(const Contact& contact, double slop) {
  for (int i = 0; i < contact.manifold.pointCount; ++i) {
    if (contact.manifold.points[static_cast<std::size_t>(i)].depth >= -slop) return true;
  }
  return false;
}

// Pairs per chunk of Prepare's parallel pass: a pair's rows (with its
// block's eigen decomposition) cost a few microseconds.
constexpr int kPairGrain = 32;
// Bundles per chunk of the coloured warm start (a bundle is well under a
// microsecond of work).
constexpr int kWarmStartBundleGrain = 16;

// Two passes. The serial one decides which contacts get rows, numbers their
// solver bodies in contact order (SolverBodies::Add: the numbering every
// step's bits follow) and gives each pair its rows' places; the second
// builds each pair's rows in its own places, on m_runner's threads. At one
// thread the rows are the same bits in the same places as one pass built.
void ContactSolver::Prepare(std::span<const BodySim> bodies, std::span<const Contact> contacts,
                            const WorldSettings& settings, double h, StepStatistics& stats) {
  m_bodies.Reset(bodies.size());
  m_pairs.clear();
  m_newPairs = 0;
  m_timedBounces = 0;
  m_split = settings.methods.positionCorrection == PositionCorrection::SplitImpulses;
  m_jointBlock = settings.methods.frictionSolve == FrictionSolve::CoupledBlock;
  m_shock = settings.methods.shockPropagation;
  m_shockTouching.clear();
  int points = 0;
  int frictions = 0;
  int blocks = 0;
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const Contact& contact = contacts[c];
    const BodySim& a = bodies[static_cast<std::size_t>(contact.bodyA)];
    const BodySim& b = bodies[static_cast<std::size_t>(contact.bodyB)];
    // A pair that contact cannot move (both immovable this step) needs no rows.
    if ((!a.IsSolverDynamic() && !b.IsSolverDynamic()) || contact.manifold.pointCount == 0) continue;

    PairRows pair;
    pair.contact = static_cast<int>(c);
    pair.bodyA = m_bodies.Add(bodies, contact.bodyA);
    pair.bodyB = m_bodies.Add(bodies, contact.bodyB);
    pair.firstPoint = points;
    pair.firstFriction = frictions;
    pair.pointCount = contact.manifold.pointCount;
    pair.normal = contact.manifold.normal;
    pair.friction = contact.friction;
    pair.hasFriction = contact.friction > 0.0;
    pair.persisted = contact.persisted && settings.methods.warmStarting;
    pair.invMassA = m_bodies.InvMass(pair.bodyA);
    pair.invMassB = m_bodies.InvMass(pair.bodyB);
    if (settings.methods.blockSolver && pair.pointCount >= 2 && pair.pointCount <= 4) pair.block = blocks++;
    points += pair.pointCount;
    stats.contactPoints += pair.pointCount;
    if (pair.hasFriction) {
      frictions += 2 * pair.pointCount;
      stats.frictionRows += 2 * pair.pointCount;
    } else {
      stats.frictionRowsSkipped += 2 * pair.pointCount;
    }
    if (!pair.persisted) ++m_newPairs;
    m_pairs.push_back(pair);
    if (m_shock) m_shockTouching.push_back(Touching(contact, settings.slop) ? 1 : 0);
  }
  if (m_shock) {
    // What gravity and the applied forces gave each body this step (shock
    // propagation's measure of the load a body puts on its supports).
    m_shockPush.resize(static_cast<std::size_t>(m_bodies.Count()));
    m_shockStart.resize(static_cast<std::size_t>(m_bodies.Count()));
    for (int i = 0; i < m_bodies.Count(); ++i) {
      const BodySim& body = bodies[static_cast<std::size_t>(m_bodies.BodyIndex(i))];
      const bool moves = m_bodies.Moves(i);
      m_shockPush[static_cast<std::size_t>(i)] =
          moves ? Vec3(body.freeLinearVelocity - body.startLinearVelocity) : Vec3::Zero();
      m_shockStart[static_cast<std::size_t>(i)] = moves ? body.startLinearVelocity : Vec3::Zero();
    }
  }
  // Every slot below is written by its pair before anything reads it.
  m_normals.resize(static_cast<std::size_t>(points));
  m_frictions.resize(static_cast<std::size_t>(frictions));
  m_cold.resize(static_cast<std::size_t>(points));
  m_blockInverses.resize(static_cast<std::size_t>(blocks));
  m_jointState.assign(m_jointBlock ? static_cast<std::size_t>(blocks) : 0, kJointUnbuilt);
  m_jointBlocks.resize(m_jointBlock ? static_cast<std::size_t>(blocks) : 0);
  m_jointCounts = JointBlockCounts{};

  std::atomic<int> timedBounces{0};
  std::atomic<int> restitutionSkipped{0};
  const JobPhase phase{.count = static_cast<int>(m_pairs.size()), .grain = kPairGrain};
  RunPhasesWith(m_runner, std::span<const JobPhase>(&phase, 1), [&](int, int begin, int end) {
    PrepareCounts counts;
    for (int p = begin; p < end; ++p) {
      PairRows& pair = m_pairs[static_cast<std::size_t>(p)];
      PreparePair(bodies, contacts[static_cast<std::size_t>(pair.contact)], settings, h, pair, counts);
    }
    timedBounces.fetch_add(counts.timedBounces, std::memory_order_relaxed);
    restitutionSkipped.fetch_add(counts.restitutionSkipped, std::memory_order_relaxed);
  });
  m_timedBounces = timedBounces.load();
  stats.timedBounces += m_timedBounces;
  stats.restitutionSkipped += restitutionSkipped.load();

  m_useWide = settings.methods.contactOrder == ContactOrder::ByColour;
  if (m_useWide) {
    m_wide.Build(m_pairs, m_normals, m_frictions, m_cold, m_blockInverses, m_bodies, m_runner);
    stats.solverColours = m_wide.ColourCount();
    stats.overflowPairs = static_cast<std::int64_t>(m_wide.OverflowPairs().size());
  }
}

void ContactSolver::PreparePair(std::span<const BodySim> bodies, const Contact& contact,
                                const WorldSettings& settings, double h, PairRows& pair,
                                PrepareCounts& counts) {
  const double invH = 1.0 / h;
  const BodySim& a = bodies[static_cast<std::size_t>(contact.bodyA)];
  const BodySim& b = bodies[static_cast<std::size_t>(contact.bodyB)];
  const Mat3& invInertiaA = m_bodies.InvInertia(pair.bodyA);
  const Mat3& invInertiaB = m_bodies.InvInertia(pair.bodyB);
  const Vec3& n = pair.normal;
  // Friction basis: t1 along the mean sliding velocity when there is one.
  if (pair.hasFriction) {
    Vec3 slide = Vec3::Zero();
    for (int i = 0; i < pair.pointCount; ++i) {
      const Vec3& p = contact.manifold.points[static_cast<std::size_t>(i)].position;
      slide += RelativeVelocity(a.linearVelocity, a.angularVelocity, p - a.center, b.linearVelocity,
                                b.angularVelocity, p - b.center);
    }
    slide -= n * n.dot(slide);
    const double speed = slide.norm() / pair.pointCount;
    pair.tangent[0] = speed > kSlidingSpeed ? Vec3(slide.normalized()) : AnyPerpendicular(n);
    pair.tangent[1] = n.cross(pair.tangent[0]);
  }

  for (int i = 0; i < pair.pointCount; ++i) {
    const std::size_t pi = static_cast<std::size_t>(i);
    const ContactPoint& cp = contact.manifold.points[pi];
    const Vec3 rA = cp.position - a.center;
    const Vec3 rB = cp.position - b.center;
    NormalRow row;
    row.j = MakeJacobian(n, rA, rB, invInertiaA, invInertiaB);
    row.mass = RowMass(row.j, pair);
    const double correction = settings.baumgarte * invH * std::max(cp.depth - settings.slop, 0.0);
    if (cp.depth < 0.0) {
      // Not touching yet: the gap may close this step, no further.
      row.target = cp.depth * invH;
    } else if (settings.methods.positionCorrection == PositionCorrection::Baumgarte) {
      row.target = correction;
    }
    PointCold cold;
    cold.armA = rA;
    cold.armB = rB;
    const bool split = settings.methods.positionCorrection == PositionCorrection::SplitImpulses;
    cold.positionTarget = split && cp.depth > 0.0 ? correction : 0.0;
    if (contact.restitution > 0.0) {
      const double vn = n.dot(
          RelativeVelocity(a.linearVelocity, a.angularVelocity, rA, b.linearVelocity, b.angularVelocity, rB));
      TimedBounce bounce;
      double acceleration = 0.0;
      if (settings.methods.bounceTiming == BounceTiming::TimeOfImpact) {
        const double u0 = n.dot(RelativeVelocity(StartVelocity(a), a.angularVelocity, rA, StartVelocity(b),
                                                 b.angularVelocity, rB));
        acceleration = (vn - u0) * invH;
        bounce =
            TimeBounce(-cp.depth, u0, acceleration, h, contact.restitution, settings.restitutionThreshold);
      }
      if (bounce.hits) {
        row.target = bounce.endSpeed;
        cold.positionTarget = (bounce.endGap + cp.depth) * invH - bounce.endSpeed;
        cold.timedBounce = true;
        ++counts.timedBounces;
      } else if (settings.methods.bounceTiming == BounceTiming::StepBoundary || bounce.tooDeep) {
        // Bounce when closing fast enough and the point touches by the end
        // of the step (a speculative point that stays apart must not bounce).
        if (vn < -settings.restitutionThreshold && cp.depth - vn * h > 0.0) {
          row.target = std::max(row.target, -contact.restitution * vn);
        }
      } else if (cp.depth < 0.0 && vn < 0.0 &&
                 settings.methods.translation == TranslationIntegrator::ExactConstantAcceleration &&
                 bounce.speed > settings.restitutionThreshold) {
        // An approach that misses the surface this step and will bounce
        // when it lands (its impact speed, which TimeBounce gives for a
        // later landing too, not its speed now, clears the threshold): an
        // untouched body closes the gap by h (vn - a h / 2), not h vn, so
        // the row asks no more of it. With h vn the row would stop the
        // point on the surface a step early, short of its impact speed: a
        // ball 14.6 mm up, falling at 0.15 m/s, stopped at 0.44 m/s at
        // 1/30 s instead of landing at 0.55 m/s next step and bouncing (the
        // fourth bounce of sphere_bounce_series, e = 0.5, was lost).
        row.target = cp.depth * invH + 0.5 * acceleration * h;
      }
    } else {
      ++counts.restitutionSkipped;
    }
    if (settings.methods.warmStarting) row.impulse = contact.normalImpulse[pi];
    if (pair.hasFriction) {
      for (int k = 0; k < 2; ++k) {
        FrictionRow friction;
        friction.j = MakeJacobian(pair.tangent[k], rA, rB, invInertiaA, invInertiaB);
        friction.mass = RowMass(friction.j, pair);
        if (settings.methods.warmStarting)
          friction.impulse = contact.frictionImpulse[pi].dot(pair.tangent[k]);
        m_frictions[static_cast<std::size_t>(pair.firstFriction + 2 * i + k)] = friction;
      }
    }
    m_normals[static_cast<std::size_t>(pair.firstPoint + i)] = row;
    m_cold[static_cast<std::size_t>(pair.firstPoint + i)] = cold;
  }
  if (pair.block >= 0) PrepareBlock(pair);
}

// Warm start: each point's accumulated impulse lambda_n n + lambda_1 t1 +
// lambda_2 t2, applied through the rows' precomputed images. Coloured: the
// colours' bundles, then the overflow pairs.
void ContactSolver::WarmStart() {
  if (m_useWide) {
    // One chain of phases: each colour, then the overflow pairs as one chunk.
    const int colours = m_wide.ColourCount();
    std::vector<JobPhase>& phases = m_phases;
    phases.clear();
    for (int colour = 0; colour < colours; ++colour) {
      phases.push_back({.count = m_wide.BundleCount(colour), .grain = kWarmStartBundleGrain});
    }
    phases.push_back({.count = m_wide.OverflowPairs().empty() ? 0 : 1, .grain = 1});
    RunPhasesWith(m_runner, phases, [this, colours](int phase, int begin, int end) {
      if (phase < colours) {
        m_wide.WarmStartRange(m_bodies, phase, begin, end);
        return;
      }
      for (const int p : m_wide.OverflowPairs()) WarmStartPair(m_pairs[static_cast<std::size_t>(p)]);
    });
    return;
  }
  for (const PairRows& pair : m_pairs) WarmStartPair(pair);
}

void ContactSolver::WarmStartPair(const PairRows& pair) {
  SolverVelocity& a = m_bodies.Velocity(pair.bodyA);
  SolverVelocity& b = m_bodies.Velocity(pair.bodyB);
  for (int i = 0; i < pair.pointCount; ++i) {
    const NormalRow& row = m_normals[static_cast<std::size_t>(pair.firstPoint + i)];
    Vec3 impulse = row.impulse * pair.normal;
    Vec3 turnA = row.impulse * row.j.imageA;
    Vec3 turnB = row.impulse * row.j.imageB;
    if (pair.hasFriction) {
      for (int k = 0; k < 2; ++k) {
        const FrictionRow& f = m_frictions[static_cast<std::size_t>(pair.firstFriction + 2 * i + k)];
        impulse += f.impulse * pair.tangent[k];
        turnA += f.impulse * f.j.imageA;
        turnB += f.impulse * f.j.imageB;
      }
    }
    a.v += pair.invMassA * impulse;
    a.w += turnA;
    b.v -= pair.invMassB * impulse;
    b.w -= turnB;
  }
}

void ContactSolver::Scatter(std::span<BodySim> bodies, bool pseudo) const {
  m_bodies.Scatter(bodies, pseudo);
}

void ContactSolver::SolveSplitImpulses(int iterations) {
  for (int it = 0; it < iterations; ++it) {
    for (const PairRows& pair : m_pairs) {
      SolverVelocity& a = m_bodies.Pseudo(pair.bodyA);
      SolverVelocity& b = m_bodies.Pseudo(pair.bodyB);
      for (int i = 0; i < pair.pointCount; ++i) {
        const std::size_t p = static_cast<std::size_t>(pair.firstPoint + i);
        PointCold& cold = m_cold[p];
        if (!cold.timedBounce && cold.positionTarget <= 0.0 && cold.pseudoImpulse == 0.0) continue;
        const NormalRow& row = m_normals[p];
        const double vn = pair.normal.dot(a.v - b.v) + row.j.angularA.dot(a.w) - row.j.angularB.dot(b.w);
        const double previous = cold.pseudoImpulse;
        // A timed bounce's row is an equality (its end gap, above or below
        // where h times the velocity would put it); the others only push.
        const double next = previous - row.mass * (vn - cold.positionTarget);
        cold.pseudoImpulse = cold.timedBounce ? next : std::max(next, 0.0);
        const double delta = cold.pseudoImpulse - previous;
        const Vec3 impulse = delta * pair.normal;
        a.v += pair.invMassA * impulse;
        a.w += delta * row.j.imageA;
        b.v -= pair.invMassB * impulse;
        b.w -= delta * row.j.imageB;
      }
    }
  }
}

void ContactSolver::StoreImpulses(std::span<Contact> contacts) const {
  for (const PairRows& pair : m_pairs) {
    Contact& contact = contacts[static_cast<std::size_t>(pair.contact)];
    for (int i = 0; i < pair.pointCount; ++i) {
      const std::size_t pi = static_cast<std::size_t>(i);
      // A timed bounce's impulse is the impact's, not a load the next step
      // should start from: warm starting it would kick the rising body.
      if (m_cold[static_cast<std::size_t>(pair.firstPoint + i)].timedBounce) {
        contact.normalImpulse[pi] = 0.0;
        contact.frictionImpulse[pi] = Vec3::Zero();
        continue;
      }
      contact.normalImpulse[pi] = m_normals[static_cast<std::size_t>(pair.firstPoint + i)].impulse;
      if (pair.hasFriction) {
        const std::size_t f = static_cast<std::size_t>(pair.firstFriction + 2 * i);
        contact.frictionImpulse[pi] =
            m_frictions[f].impulse * pair.tangent[0] + m_frictions[f + 1].impulse * pair.tangent[1];
      } else {
        contact.frictionImpulse[pi] = Vec3::Zero();
      }
    }
  }
}

}  // namespace talus
