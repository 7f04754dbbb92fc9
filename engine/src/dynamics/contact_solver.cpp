// Sequential Impulses on contact and friction rows; the constraint
// derivations are in dynamics/contact_solver.h.
#include "dynamics/contact_solver.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace talus {
namespace {

// Below this tangential speed (m/s) the friction basis is a fixed function
// of the normal instead of the sliding direction: a direction computed from
// round-off would only add noise.
constexpr double kSlidingSpeed = 1e-9;

// Most a non-linear Gauss-Seidel sweep moves one point, metres (Box2D's
// b2_maxLinearCorrection): a deep overlap is pushed out over several steps
// instead of launched.
constexpr double kMaxCorrection = 0.2;

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
  m_newPairs.clear();
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
    pair.persisted = contact.persisted && settings.warmStarting;
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
      } else if (settings.positionCorrection == PositionCorrection::Baumgarte) {
        row.target = correction;
      }
      const bool split = settings.positionCorrection == PositionCorrection::SplitImpulses;
      row.positionTarget = split && cp.depth > 0.0 ? correction : 0.0;
      // The surface points of A and B the midpoint stands for, half the
      // depth either side along n, kept in body axes for the position pass.
      row.localAnchorA = a.orientation.conjugate() * (row.rA - 0.5 * cp.depth * n);
      row.localAnchorB = b.orientation.conjugate() * (row.rB + 0.5 * cp.depth * n);
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
    if (settings.blockSolver && pair.pointCount >= 2 && pair.pointCount <= 4) PrepareBlock(pair);
    stats.contactPoints += pair.pointCount;
    if (pair.hasFriction) {
      stats.frictionRows += 2 * pair.pointCount;
    } else {
      stats.frictionRowsSkipped += 2 * pair.pointCount;
    }
    if (!pair.persisted) m_newPairs.push_back(static_cast<int>(m_pairs.size()));
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

namespace {

// The velocities of a pair's two bodies, loaded once per pass over the pair
// and written back at its end.
struct PairVelocities {
  Vec3 vA, wA, vB, wB;
};

PairVelocities Load(const BodySim& a, const BodySim& b) {
  return {a.linearVelocity, a.angularVelocity, b.linearVelocity, b.angularVelocity};
}

void Store(const PairVelocities& v, BodySim& a, BodySim& b) {
  a.linearVelocity = v.vA;
  a.angularVelocity = v.wA;
  b.linearVelocity = v.vB;
  b.angularVelocity = v.wB;
}

}  // namespace

void ContactSolver::PrepareBlock(PairRows& pair) const {
  const int count = pair.pointCount;
  Eigen::Matrix4d k = Eigen::Matrix4d::Identity();
  const Vec3& n = pair.normal;
  Vec3 ra[4], rb[4];
  for (int i = 0; i < count; ++i) {
    const PointRow& row = m_points[static_cast<std::size_t>(pair.firstPoint + i)];
    ra[i] = row.rA.cross(n);
    rb[i] = row.rB.cross(n);
  }
  for (int i = 0; i < count; ++i) {
    for (int j = 0; j < count; ++j) {
      k(i, j) = pair.invMassA + pair.invMassB + ra[i].dot(pair.invInertiaA * ra[j]) +
                rb[i].dot(pair.invInertiaB * rb[j]);
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(k);
  const Eigen::Vector4d values = eigen.eigenvalues();
  const double largest = values.cwiseAbs().maxCoeff();
  Eigen::Vector4d inverse = Eigen::Vector4d::Zero();
  for (int i = 0; i < 4; ++i) {
    if (values[i] > 1e-9 * largest) inverse[i] = 1.0 / values[i];
  }
  pair.blockInverse = eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
  for (int i = count; i < 4; ++i) {
    pair.blockInverse.row(i).setZero();
    pair.blockInverse.col(i).setZero();
  }
  pair.block = true;
}

bool ContactSolver::SolveNormalBlock(std::span<BodySim> bodies, const PairRows& pair) {
  BodySim& a = bodies[static_cast<std::size_t>(pair.bodyA)];
  BodySim& b = bodies[static_cast<std::size_t>(pair.bodyB)];
  PairVelocities v = Load(a, b);
  Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
  Eigen::Vector4d lambda = Eigen::Vector4d::Zero();
  for (int i = 0; i < pair.pointCount; ++i) {
    const PointRow& row = m_points[static_cast<std::size_t>(pair.firstPoint + i)];
    const double vn = pair.normal.dot(RelativeVelocity(v.vA, v.wA, row.rA, v.vB, v.wB, row.rB));
    rhs[i] = row.target - vn;
    lambda[i] = row.normalImpulse;
  }
  const Eigen::Vector4d delta = pair.blockInverse * rhs;
  for (int i = 0; i < pair.pointCount; ++i) {
    if (lambda[i] + delta[i] < 0.0) return false;
  }
  for (int i = 0; i < pair.pointCount; ++i) {
    PointRow& row = m_points[static_cast<std::size_t>(pair.firstPoint + i)];
    row.normalImpulse = lambda[i] + delta[i];
    NoteChange(pair, delta[i], row.normalMass);
    const Vec3 impulse = delta[i] * pair.normal;
    v.vA += pair.invMassA * impulse;
    v.wA += pair.invInertiaA * row.rA.cross(impulse);
    v.vB -= pair.invMassB * impulse;
    v.wB -= pair.invInertiaB * row.rB.cross(impulse);
  }
  Store(v, a, b);
  return true;
}

// The normal rows of one pair: accumulated impulse clamped to [0, inf).
void ContactSolver::SolveNormals(std::span<BodySim> bodies, const PairRows& pair) {
  if (pair.block && SolveNormalBlock(bodies, pair)) return;
  BodySim& a = bodies[static_cast<std::size_t>(pair.bodyA)];
  BodySim& b = bodies[static_cast<std::size_t>(pair.bodyB)];
  PairVelocities v = Load(a, b);
  for (int i = 0; i < pair.pointCount; ++i) {
    PointRow& row = m_points[static_cast<std::size_t>(pair.firstPoint + i)];
    const double vn = pair.normal.dot(RelativeVelocity(v.vA, v.wA, row.rA, v.vB, v.wB, row.rB));
    const double previous = row.normalImpulse;
    row.normalImpulse = std::max(previous - row.normalMass * (vn - row.target), 0.0);
    NoteChange(pair, row.normalImpulse - previous, row.normalMass);
    const Vec3 impulse = (row.normalImpulse - previous) * pair.normal;
    v.vA += pair.invMassA * impulse;
    v.wA += pair.invInertiaA * row.rA.cross(impulse);
    v.vB -= pair.invMassB * impulse;
    v.wB -= pair.invInertiaB * row.rB.cross(impulse);
  }
  Store(v, a, b);
}

// The friction rows of one pair, each bounded by mu times its point's
// current normal impulse.
void ContactSolver::SolveFriction(std::span<BodySim> bodies, const PairRows& pair) {
  BodySim& a = bodies[static_cast<std::size_t>(pair.bodyA)];
  BodySim& b = bodies[static_cast<std::size_t>(pair.bodyB)];
  PairVelocities v = Load(a, b);
  for (int i = 0; i < pair.pointCount; ++i) {
    PointRow& row = m_points[static_cast<std::size_t>(pair.firstPoint + i)];
    const double bound = pair.friction * row.normalImpulse;
    for (int k = 0; k < 2; ++k) {
      const Vec3& t = pair.tangent[k];
      const double vt = t.dot(RelativeVelocity(v.vA, v.wA, row.rA, v.vB, v.wB, row.rB));
      const double old = row.tangentImpulse[k];
      row.tangentImpulse[k] = std::clamp(old - row.tangentMass[k] * vt, -bound, bound);
      NoteChange(pair, row.tangentImpulse[k] - old, row.tangentMass[k]);
      const Vec3 impulse = (row.tangentImpulse[k] - old) * t;
      v.vA += pair.invMassA * impulse;
      v.wA += pair.invInertiaA * row.rA.cross(impulse);
      v.vB -= pair.invMassB * impulse;
      v.wB -= pair.invInertiaB * row.rB.cross(impulse);
    }
  }
  Store(v, a, b);
}

// Each iteration sweeps every normal row, then every friction row (the
// order Bullet uses). Measured on a 10-box column: interleaving friction
// after each point's normal row left ten times the residual rocking
// (0.1 rad/s against 0.01 rad/s at 10 iterations), because a corner's
// friction row then reads a normal impulse the other corners have not yet
// balanced. The friction bound still follows the normal impulse as it
// changes: every friction pass reads the current values.
//
// Past `minIterations`, when some pair is new this step, further sweeps
// over all rows go on while the last one still changed a row of a new pair
// by more than `tolerance` (m/s), up to `maxIterations` sweeps in all. A new
// pair has no accumulated impulse to start from: under a stack whose
// contacts are all new, the load must diffuse through the chain one contact
// per sweep, and ten sweeps leave a 10-box column sagging 1.5 cm. Measured
// alternatives: sweeping everything to convergence every step cost 6x the
// solver time on the 1240-cube pyramid (its warm-started rows never settle
// to 1e-3 m/s in ten sweeps); sweeping the new pairs' rows alone pushed
// bodies into the contacts left unsolved and the pyramid drifted 0.45 m.
int ContactSolver::SolveVelocities(std::span<BodySim> bodies, int minIterations, int maxIterations,
                                   double tolerance) {
  int sweeps = 0;
  for (; sweeps < minIterations; ++sweeps) {
    for (const PairRows& pair : m_pairs) SolveNormals(bodies, pair);
    for (const PairRows& pair : m_pairs) {
      if (pair.hasFriction) SolveFriction(bodies, pair);
    }
  }
  if (m_newPairs.empty()) return sweeps;
  for (; sweeps < maxIterations; ++sweeps) {
    m_largestChange = 0.0;
    for (const PairRows& pair : m_pairs) SolveNormals(bodies, pair);
    for (const PairRows& pair : m_pairs) {
      if (pair.hasFriction) SolveFriction(bodies, pair);
    }
    if (m_largestChange <= tolerance) return sweeps + 1;
  }
  return sweeps;
}

void ContactSolver::SolveSplitImpulses(std::span<BodySim> bodies, int iterations) {
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

void ContactSolver::NoteChange(const PairRows& pair, double impulse, double mass) {
  if (!pair.persisted && mass > 0.0) m_largestChange = std::max(m_largestChange, std::abs(impulse) / mass);
}

namespace {

// Turns `q` by the small rotation vector `theta` (radians): q + (theta, 0)
// q / 2, normalised (the first-order exponential map, as Box2D and Jolt).
void Turn(Quat& q, const Vec3& theta) {
  const Quat dq(0.0, 0.5 * theta.x(), 0.5 * theta.y(), 0.5 * theta.z());
  q.coeffs() += (dq * q).coeffs();
  q.normalize();
}

}  // namespace

int ContactSolver::SolveNonlinearPositions(std::span<BodySim> bodies, int iterations, double beta,
                                           double slop) {
  int sweeps = 0;
  for (; sweeps < iterations;) {
    double deepest = 0.0;
    for (const PairRows& pair : m_pairs) {
      BodySim& a = bodies[static_cast<std::size_t>(pair.bodyA)];
      BodySim& b = bodies[static_cast<std::size_t>(pair.bodyB)];
      const Vec3& n = pair.normal;
      for (int i = 0; i < pair.pointCount; ++i) {
        const PointRow& row = m_points[static_cast<std::size_t>(pair.firstPoint + i)];
        const Vec3 rA = a.orientation * row.localAnchorA;
        const Vec3 rB = b.orientation * row.localAnchorB;
        const double depth = n.dot((b.center + rB) - (a.center + rA));
        deepest = std::max(deepest, depth);
        const double correction = std::clamp(beta * (depth - slop), 0.0, kMaxCorrection);
        if (correction <= 0.0) continue;
        const double mass =
            EffectiveMass(n, rA, rB, pair.invMassA, pair.invMassB, pair.invInertiaA, pair.invInertiaB);
        const Vec3 impulse = (mass * correction) * n;
        a.center += pair.invMassA * impulse;
        b.center -= pair.invMassB * impulse;
        if (pair.invMassA > 0.0) Turn(a.orientation, pair.invInertiaA * rA.cross(impulse));
        if (pair.invMassB > 0.0) Turn(b.orientation, -(pair.invInertiaB * rB.cross(impulse)));
      }
    }
    ++sweeps;
    if (deepest <= 3.0 * slop) break;
  }
  for (const PairRows& pair : m_pairs) {
    if (pair.invMassA > 0.0) bodies[static_cast<std::size_t>(pair.bodyA)].UpdateWorldInertia();
    if (pair.invMassB > 0.0) bodies[static_cast<std::size_t>(pair.bodyB)].UpdateWorldInertia();
  }
  return sweeps;
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
