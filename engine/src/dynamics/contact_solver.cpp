// Sequential Impulses on contact and friction rows; the constraint
// derivations are in dynamics/contact_solver.h.
#include "dynamics/contact_solver.h"

#include <algorithm>
#include <cassert>
#include <cmath>

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

// Velocity of A relative to B at the contact point (see header).
Vec3 RelativeVelocity(const Vec3& vA, const Vec3& wA, const Vec3& rA, const Vec3& vB, const Vec3& wB,
                      const Vec3& rB) {
  return (vA + wA.cross(rA)) - (vB + wB.cross(rB));
}

// 1 / (J M^-1 J^T) of a row along `axis` (the effective mass).
double EffectiveMass(const Vec3& axis, const Vec3& rA, const Vec3& rB, double invMassA, double invMassB,
                     const Mat3& invInertiaA, const Mat3& invInertiaB) {
  const Vec3 ra = rA.cross(axis);
  const Vec3 rb = rB.cross(axis);
  const double k = invMassA + invMassB + ra.dot(invInertiaA * ra) + rb.dot(invInertiaB * rb);
  return k > 0.0 ? 1.0 / k : 0.0;
}

}  // namespace

void ContactSolver::Prepare(std::span<const BodySim> bodies, std::span<const Contact> contacts,
                            const WorldSettings& settings, double h, StepStatistics& stats) {
  m_pairs.clear();
  m_points.clear();
  const double invH = 1.0 / h;
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const Contact& contact = contacts[c];
    const BodySim& a = bodies[static_cast<std::size_t>(contact.bodyA)];
    const BodySim& b = bodies[static_cast<std::size_t>(contact.bodyB)];
    const bool movesA = a.IsSolverDynamic();
    const bool movesB = b.IsSolverDynamic();
    // A pair that contact cannot move (both immovable this step) needs no rows.
    if ((!movesA && !movesB) || contact.manifold.pointCount == 0) continue;

    PairRows pair;
    pair.contact = static_cast<int>(c);
    pair.bodyA = contact.bodyA;
    pair.bodyB = contact.bodyB;
    pair.firstPoint = static_cast<int>(m_points.size());
    pair.pointCount = contact.manifold.pointCount;
    pair.normal = contact.manifold.normal;
    pair.friction = contact.friction;
    pair.hasFriction = contact.friction > 0.0;
    pair.invMassA = movesA ? a.invMass : 0.0;
    pair.invMassB = movesB ? b.invMass : 0.0;
    pair.invInertiaA = movesA ? a.invInertiaWorld : Mat3::Zero();
    pair.invInertiaB = movesB ? b.invInertiaWorld : Mat3::Zero();
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
      PointRow row;
      row.rA = cp.position - a.center;
      row.rB = cp.position - b.center;
      row.normalMass =
          EffectiveMass(n, row.rA, row.rB, pair.invMassA, pair.invMassB, pair.invInertiaA, pair.invInertiaB);
      const double vn = n.dot(RelativeVelocity(a.linearVelocity, a.angularVelocity, row.rA, b.linearVelocity,
                                               b.angularVelocity, row.rB));
      const double correction = settings.baumgarte * invH * std::max(cp.depth - settings.slop, 0.0);
      if (cp.depth < 0.0) {
        // Not touching yet: the gap may close this step, no further.
        row.target = cp.depth * invH;
      } else if (!settings.splitImpulses) {
        row.target = correction;
      }
      row.positionTarget = settings.splitImpulses && cp.depth > 0.0 ? correction : 0.0;
      if (contact.restitution > 0.0) {
        // Bounce when closing fast enough and the point touches by the end of
        // the step (a speculative point that stays apart must not bounce).
        if (vn < -settings.restitutionThreshold && cp.depth - vn * h > 0.0) {
          row.target = std::max(row.target, -contact.restitution * vn);
        }
      } else {
        ++stats.restitutionSkipped;
      }
      if (pair.hasFriction) {
        for (int k = 0; k < 2; ++k) {
          row.tangentMass[k] = EffectiveMass(pair.tangent[k], row.rA, row.rB, pair.invMassA, pair.invMassB,
                                             pair.invInertiaA, pair.invInertiaB);
        }
      }
      if (settings.warmStarting) {
        row.normalImpulse = contact.normalImpulse[pi];
        if (pair.hasFriction) {
          for (int k = 0; k < 2; ++k)
            row.tangentImpulse[k] = contact.frictionImpulse[pi].dot(pair.tangent[k]);
        }
      }
      m_points.push_back(row);
    }
    stats.contactPoints += pair.pointCount;
    if (pair.hasFriction) {
      stats.frictionRows += 2 * pair.pointCount;
    } else {
      stats.frictionRowsSkipped += 2 * pair.pointCount;
    }
    m_pairs.push_back(pair);
  }
}

void ContactSolver::WarmStart(std::span<BodySim> bodies) const {
  for (const PairRows& pair : m_pairs) {
    BodySim& a = bodies[static_cast<std::size_t>(pair.bodyA)];
    BodySim& b = bodies[static_cast<std::size_t>(pair.bodyB)];
    for (int i = 0; i < pair.pointCount; ++i) {
      const PointRow& row = m_points[static_cast<std::size_t>(pair.firstPoint + i)];
      Vec3 impulse = row.normalImpulse * pair.normal;
      if (pair.hasFriction)
        impulse += row.tangentImpulse[0] * pair.tangent[0] + row.tangentImpulse[1] * pair.tangent[1];
      a.linearVelocity += pair.invMassA * impulse;
      a.angularVelocity += pair.invInertiaA * row.rA.cross(impulse);
      b.linearVelocity -= pair.invMassB * impulse;
      b.angularVelocity -= pair.invInertiaB * row.rB.cross(impulse);
    }
  }
}

// One Gauss-Seidel pass over a pair: per point the normal row first, then
// its two friction rows bounded by the normal impulse just updated (the
// write-up: the friction limit follows every change of the normal impulse).
void ContactSolver::SolvePair(std::span<BodySim> bodies, const PairRows& pair) {
  BodySim& a = bodies[static_cast<std::size_t>(pair.bodyA)];
  BodySim& b = bodies[static_cast<std::size_t>(pair.bodyB)];
  Vec3 vA = a.linearVelocity, wA = a.angularVelocity;
  Vec3 vB = b.linearVelocity, wB = b.angularVelocity;
  const auto apply = [&](const Vec3& impulse, const PointRow& row) {
    vA += pair.invMassA * impulse;
    wA += pair.invInertiaA * row.rA.cross(impulse);
    vB -= pair.invMassB * impulse;
    wB -= pair.invInertiaB * row.rB.cross(impulse);
  };
  for (int i = 0; i < pair.pointCount; ++i) {
    PointRow& row = m_points[static_cast<std::size_t>(pair.firstPoint + i)];
    const double vn = pair.normal.dot(RelativeVelocity(vA, wA, row.rA, vB, wB, row.rB));
    const double previous = row.normalImpulse;
    row.normalImpulse = std::max(previous - row.normalMass * (vn - row.target), 0.0);
    apply((row.normalImpulse - previous) * pair.normal, row);
    if (!pair.hasFriction) continue;
    const double bound = pair.friction * row.normalImpulse;
    for (int k = 0; k < 2; ++k) {
      const Vec3& t = pair.tangent[k];
      const double vt = t.dot(RelativeVelocity(vA, wA, row.rA, vB, wB, row.rB));
      const double old = row.tangentImpulse[k];
      row.tangentImpulse[k] = std::clamp(old - row.tangentMass[k] * vt, -bound, bound);
      apply((row.tangentImpulse[k] - old) * t, row);
    }
  }
  a.linearVelocity = vA;
  a.angularVelocity = wA;
  b.linearVelocity = vB;
  b.angularVelocity = wB;
}

void ContactSolver::SolveVelocities(std::span<BodySim> bodies, int iterations) {
  for (int it = 0; it < iterations; ++it) {
    for (const PairRows& pair : m_pairs) SolvePair(bodies, pair);
  }
}

void ContactSolver::SolvePositions(std::span<BodySim> bodies, int iterations) {
  for (int it = 0; it < iterations; ++it) {
    for (const PairRows& pair : m_pairs) {
      BodySim& a = bodies[static_cast<std::size_t>(pair.bodyA)];
      BodySim& b = bodies[static_cast<std::size_t>(pair.bodyB)];
      for (int i = 0; i < pair.pointCount; ++i) {
        PointRow& row = m_points[static_cast<std::size_t>(pair.firstPoint + i)];
        if (row.positionTarget <= 0.0 && row.pseudoImpulse == 0.0) continue;
        const double vn = pair.normal.dot(RelativeVelocity(a.pseudoLinear, a.pseudoAngular, row.rA,
                                                           b.pseudoLinear, b.pseudoAngular, row.rB));
        const double previous = row.pseudoImpulse;
        row.pseudoImpulse = std::max(previous - row.normalMass * (vn - row.positionTarget), 0.0);
        const Vec3 impulse = (row.pseudoImpulse - previous) * pair.normal;
        a.pseudoLinear += pair.invMassA * impulse;
        a.pseudoAngular += pair.invInertiaA * row.rA.cross(impulse);
        b.pseudoLinear -= pair.invMassB * impulse;
        b.pseudoAngular -= pair.invInertiaB * row.rB.cross(impulse);
      }
    }
  }
}

void ContactSolver::StoreImpulses(std::span<Contact> contacts) const {
  for (const PairRows& pair : m_pairs) {
    Contact& contact = contacts[static_cast<std::size_t>(pair.contact)];
    for (int i = 0; i < pair.pointCount; ++i) {
      const PointRow& row = m_points[static_cast<std::size_t>(pair.firstPoint + i)];
      const std::size_t pi = static_cast<std::size_t>(i);
      contact.normalImpulse[pi] = row.normalImpulse;
      contact.frictionImpulse[pi] =
          pair.hasFriction
              ? Vec3(row.tangentImpulse[0] * pair.tangent[0] + row.tangentImpulse[1] * pair.tangent[1])
              : Vec3::Zero();
    }
  }
}

}  // namespace talus
