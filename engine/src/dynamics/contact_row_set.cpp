// ContactRowSet: building the rows of one step's contacts (Prepare) and
// storing their impulses back. The derivations and the data layout are in
// dynamics/contact_row_set.h.
#include "dynamics/contact_row_set.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "dynamics/adaptive_friction.h"
#include "dynamics/bounce_timing.h"
#include "dynamics/manifold_friction.h"

namespace talus {
namespace {

// Pairs per chunk of Prepare's parallel pass: a pair's rows (with its
// block's pseudo-inverse) cost a few microseconds.
constexpr int kPairGrain = 32;

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

// Friction basis: t1 along the pair's mean sliding velocity when there is
// one, else a fixed perpendicular of n; t2 = n x t1.
void ChooseTangents(const BodySim& a, const BodySim& b, const ContactManifold& manifold, PairRows& pair) {
  const Vec3& n = pair.normal;
  Vec3 slide = Vec3::Zero();
  for (int i = 0; i < pair.pointCount; ++i) {
    const Vec3& p = manifold.points[static_cast<std::size_t>(i)].position;
    slide += RelativeVelocity(a.linearVelocity, a.angularVelocity, p - a.center, b.linearVelocity,
                              b.angularVelocity, p - b.center);
  }
  slide -= n * n.dot(slide);
  const double speed = slide.norm() / pair.pointCount;
  pair.tangent[0] = speed > kSlidingSpeed ? Vec3(slide.normalized()) : AnyPerpendicular(n);
  pair.tangent[1] = n.cross(pair.tangent[0]);
}

// Restitution's part of a point's targets (header: the bounce at the step
// boundary, the timed bounce with its position row, the speculative
// approach that lands later), on top of the resting target in `row`.
// Returns whether the point bounces inside the step.
bool ApplyRestitution(const BodySim& a, const BodySim& b, const Vec3& n, const Vec3& rA, const Vec3& rB,
                      const ContactPoint& cp, double restitution, const WorldSettings& settings, double h,
                      NormalRow& row, PointCold& cold) {
  const double invH = 1.0 / h;
  const double vn = n.dot(
      RelativeVelocity(a.linearVelocity, a.angularVelocity, rA, b.linearVelocity, b.angularVelocity, rB));
  TimedBounce bounce;
  double acceleration = 0.0;
  if (settings.methods.bounceTiming == BounceTiming::TimeOfImpact) {
    const double u0 = n.dot(
        RelativeVelocity(StartVelocity(a), a.angularVelocity, rA, StartVelocity(b), b.angularVelocity, rB));
    acceleration = (vn - u0) * invH;
    bounce = TimeBounce(-cp.depth, u0, acceleration, h, restitution, settings.restitutionThreshold);
  }
  if (bounce.hits) {
    row.target = bounce.endSpeed;
    cold.positionTarget = (bounce.endGap + cp.depth) * invH - bounce.endSpeed;
    cold.timedBounce = true;
    return true;
  }
  if (settings.methods.bounceTiming == BounceTiming::StepBoundary || bounce.tooDeep) {
    // Bounce when closing fast enough and the point touches by the end
    // of the step (a speculative point that stays apart must not bounce).
    if (vn < -settings.restitutionThreshold && cp.depth - vn * h > 0.0) {
      row.target = std::max(row.target, -restitution * vn);
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
  return false;
}

// Whether a pair is solved as a normal block: 2 to 4 points with the block
// solver selected.
bool UsesNormalBlock(const WorldSettings& settings, int pointCount) {
  return settings.methods.blockSolver && pointCount >= 2 && pointCount <= 4;
}

// Whether a pair with friction gets the manifold's rows: always under
// PerManifold; under Adaptive unless a body of it is under load
// (MarkBodiesUnderLoad, dynamics/adaptive_friction.h).
bool UsesManifoldFriction(const WorldSettings& settings, const Contact& contact,
                          std::span<const unsigned char> underLoad) {
  switch (settings.methods.frictionSolve) {
    case FrictionSolve::PerManifold:
      return true;
    case FrictionSolve::Adaptive:
      return underLoad[static_cast<std::size_t>(contact.bodyA)] == 0 &&
             underLoad[static_cast<std::size_t>(contact.bodyB)] == 0;
    default:
      return false;
  }
}

// The inverse mass contact impulses see: zero for a body they cannot move.
double SolverInvMass(const BodySim& body) { return body.IsSolverDynamic() ? body.invMass : 0.0; }

// Whether any pair may get the manifold's rows (their levers are stored).
bool MayUseManifoldFriction(const WorldSettings& settings) {
  return settings.methods.frictionSolve == FrictionSolve::PerManifold ||
         settings.methods.frictionSolve == FrictionSolve::Adaptive;
}

}  // namespace

// Two passes. The serial one decides which contacts get rows, numbers their
// solver bodies in contact order (SolverBodies::Add: the numbering every
// step's bits follow) and gives each pair its rows' places; the second
// builds each pair's rows in its own places, on `runner`'s threads. At one
// thread the rows are the same bits in the same places as one pass built.
void ContactRowSet::Prepare(std::span<const BodySim> bodies, std::span<const Contact> contacts,
                            const WorldSettings& settings, double h, const PhaseRunner& runner,
                            StepStatistics& stats) {
  m_bodies.Reset(bodies.size());
  m_pairs.clear();
  m_newPairs = 0;
  m_timedBounces = 0;
  if (settings.methods.frictionSolve == FrictionSolve::Adaptive)
    MarkBodiesUnderLoad(bodies, contacts, settings, h);
  const RowTotals totals = AddPairHeaders(bodies, contacts, settings, stats);
  // Every slot below is written by its pair before anything reads it.
  m_normals.resize(static_cast<std::size_t>(totals.points));
  m_frictions.resize(static_cast<std::size_t>(totals.frictions));
  // Read only where written; the default mode never touches it.
  m_levers.resize(MayUseManifoldFriction(settings) ? static_cast<std::size_t>(totals.points) : 0);
  m_cold.resize(static_cast<std::size_t>(totals.points));
  m_blockInverses.resize(static_cast<std::size_t>(totals.blocks));
  BuildPairsOnThreads(bodies, contacts, settings, h, runner, stats);
}

// The bodies whose pairs take the coupled block under Adaptive: every body
// of a group that contact joins (moving bodies touching, directly or
// through others; immovable bodies join nothing) in which some pair's load
// calls for it (AdaptiveNeedsCoupledBlock). A heavy load's weight passes
// through every support under it down to the ground, so the whole group
// is solved one way: measured, a 1-10-100-1000 kg column at 5 sweeps
// with only its loaded pairs on the coupled block lost its top box, and a
// 1000:1 load on a pyramid at 1/960 s, with the pairs that had not yet
// felt it on manifold rows, collapsed after 2.8 s; both held with the
// group on either kind (docs/dynamics.md, "Adaptive friction").
void ContactRowSet::MarkBodiesUnderLoad(std::span<const BodySim> bodies, std::span<const Contact> contacts,
                                        const WorldSettings& settings, double h) {
  const std::size_t count = bodies.size();
  m_group.resize(count);
  for (std::size_t i = 0; i < count; ++i) m_group[i] = static_cast<int>(i);
  const auto root = [this](int i) {
    while (m_group[static_cast<std::size_t>(i)] != i) {
      // Path halving: each visited body points two up.
      const int up = m_group[static_cast<std::size_t>(m_group[static_cast<std::size_t>(i)])];
      m_group[static_cast<std::size_t>(i)] = up;
      i = up;
    }
    return i;
  };
  for (const Contact& contact : contacts) {
    if (!bodies[static_cast<std::size_t>(contact.bodyA)].IsSolverDynamic() ||
        !bodies[static_cast<std::size_t>(contact.bodyB)].IsSolverDynamic() ||
        contact.manifold.pointCount == 0) {
      continue;
    }
    const int a = root(contact.bodyA);
    const int b = root(contact.bodyB);
    // The lower index becomes the root: the grouping depends on the
    // contacts only, never on a thread.
    if (a != b) m_group[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }
  m_underLoad.assign(count, 0);
  const double gravity = settings.gravity.norm();
  for (const Contact& contact : contacts) {
    const BodySim& a = bodies[static_cast<std::size_t>(contact.bodyA)];
    const BodySim& b = bodies[static_cast<std::size_t>(contact.bodyB)];
    const double invMassA = SolverInvMass(a);
    const double invMassB = SolverInvMass(b);
    if ((invMassA == 0.0 && invMassB == 0.0) || contact.manifold.pointCount == 0 || contact.friction <= 0.0) {
      continue;
    }
    if (!AdaptiveNeedsCoupledBlock(contact, invMassA, invMassB, gravity, h)) continue;
    m_underLoad[static_cast<std::size_t>(root(invMassA > 0.0 ? contact.bodyA : contact.bodyB))] = 1;
  }
  for (std::size_t i = 0; i < count; ++i) {
    m_underLoad[i] = m_underLoad[static_cast<std::size_t>(root(static_cast<int>(i)))];
  }
}

ContactRowSet::RowTotals ContactRowSet::AddPairHeaders(std::span<const BodySim> bodies,
                                                       std::span<const Contact> contacts,
                                                       const WorldSettings& settings, StepStatistics& stats) {
  RowTotals totals;
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const Contact& contact = contacts[c];
    const BodySim& a = bodies[static_cast<std::size_t>(contact.bodyA)];
    const BodySim& b = bodies[static_cast<std::size_t>(contact.bodyB)];
    // A pair that contact cannot move (both immovable this step) needs no rows.
    if ((!a.IsSolverDynamic() && !b.IsSolverDynamic()) || contact.manifold.pointCount == 0) continue;
    const PairRows pair = MakePairHeader(bodies, contact, static_cast<int>(c), settings, totals);
    stats.contactPoints += pair.pointCount;
    if (pair.manifoldFriction) {
      stats.frictionRows += ManifoldFrictionRowCount(pair.pointCount);
    } else if (pair.hasFriction) {
      stats.frictionRows += 2 * pair.pointCount;
    } else {
      stats.frictionRowsSkipped += 2 * pair.pointCount;
    }
    if (!pair.persisted) ++m_newPairs;
    m_pairs.push_back(pair);
  }
  return totals;
}

PairRows ContactRowSet::MakePairHeader(std::span<const BodySim> bodies, const Contact& contact, int c,
                                       const WorldSettings& settings, RowTotals& totals) {
  PairRows pair;
  pair.contact = c;
  pair.bodyA = m_bodies.Add(bodies, contact.bodyA);
  pair.bodyB = m_bodies.Add(bodies, contact.bodyB);
  pair.firstPoint = totals.points;
  pair.firstFriction = totals.frictions;
  pair.pointCount = contact.manifold.pointCount;
  pair.normal = contact.manifold.normal;
  pair.friction = contact.friction;
  pair.hasFriction = contact.friction > 0.0;
  pair.invMassA = m_bodies.InvMass(pair.bodyA);
  pair.invMassB = m_bodies.InvMass(pair.bodyB);
  pair.manifoldFriction = pair.hasFriction && UsesManifoldFriction(settings, contact, m_underLoad);
  pair.persisted = contact.persisted && settings.methods.warmStarting;
  if (UsesNormalBlock(settings, pair.pointCount)) pair.block = totals.blocks++;
  totals.points += pair.pointCount;
  if (pair.manifoldFriction) {
    totals.frictions += ManifoldFrictionRowCount(pair.pointCount);
  } else if (pair.hasFriction) {
    totals.frictions += 2 * pair.pointCount;
  }
  return pair;
}

void ContactRowSet::BuildPairsOnThreads(std::span<const BodySim> bodies, std::span<const Contact> contacts,
                                        const WorldSettings& settings, double h, const PhaseRunner& runner,
                                        StepStatistics& stats) {
  std::atomic<int> timedBounces{0};
  std::atomic<int> restitutionSkipped{0};
  const JobPhase phase{.count = static_cast<int>(m_pairs.size()), .grain = kPairGrain};
  RunPhasesWith(runner, std::span<const JobPhase>(&phase, 1), [&](int, int begin, int end) {
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
}

void ContactRowSet::PreparePair(std::span<const BodySim> bodies, const Contact& contact,
                                const WorldSettings& settings, double h, PairRows& pair,
                                PrepareCounts& counts) {
  const BodySim& a = bodies[static_cast<std::size_t>(contact.bodyA)];
  const BodySim& b = bodies[static_cast<std::size_t>(contact.bodyB)];
  if (pair.hasFriction) ChooseTangents(a, b, contact.manifold, pair);
  for (int i = 0; i < pair.pointCount; ++i) PreparePoint(a, b, contact, i, settings, h, pair, counts);
  if (pair.manifoldFriction) PrepareManifoldFriction(a, b, contact, settings, pair);
  if (pair.block >= 0) PrepareBlock(pair);
}

void ContactRowSet::PreparePoint(const BodySim& a, const BodySim& b, const Contact& contact, int i,
                                 const WorldSettings& settings, double h, const PairRows& pair,
                                 PrepareCounts& counts) {
  const double invH = 1.0 / h;
  const std::size_t pi = static_cast<std::size_t>(i);
  const ContactPoint& cp = contact.manifold.points[pi];
  const Vec3& n = pair.normal;
  const Vec3 rA = cp.position - a.center;
  const Vec3 rB = cp.position - b.center;
  NormalRow row;
  row.j = MakeRowJacobian(n, rA, rB, m_bodies.InvInertia(pair.bodyA), m_bodies.InvInertia(pair.bodyB));
  row.mass = RowEffectiveMass(row.j, pair.invMassA, pair.invMassB);
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
    if (ApplyRestitution(a, b, n, rA, rB, cp, contact.restitution, settings, h, row, cold))
      ++counts.timedBounces;
  } else {
    ++counts.restitutionSkipped;
  }
  if (settings.methods.warmStarting) row.impulse = contact.normalImpulse[pi];
  if (pair.hasFriction && !pair.manifoldFriction) PrepareFrictionRows(contact, i, rA, rB, settings, pair);
  m_normals[static_cast<std::size_t>(pair.firstPoint + i)] = row;
  m_cold[static_cast<std::size_t>(pair.firstPoint + i)] = cold;
}

void ContactRowSet::PrepareFrictionRows(const Contact& contact, int i, const Vec3& rA, const Vec3& rB,
                                        const WorldSettings& settings, const PairRows& pair) {
  for (int k = 0; k < 2; ++k) {
    FrictionRow friction;
    friction.j = MakeRowJacobian(pair.tangent[k], rA, rB, m_bodies.InvInertia(pair.bodyA),
                                 m_bodies.InvInertia(pair.bodyB));
    friction.mass = RowEffectiveMass(friction.j, pair.invMassA, pair.invMassB);
    if (settings.methods.warmStarting) {
      friction.impulse = contact.frictionImpulse[static_cast<std::size_t>(i)].dot(pair.tangent[k]);
    }
    m_frictions[static_cast<std::size_t>(pair.firstFriction + 2 * i + k)] = friction;
  }
}

// The slip rows at the pair's centre of pressure, the spin row about n, the
// levers, and the warm start summed from the stored
// per-point vectors (dynamics/manifold_friction.h).
void ContactRowSet::PrepareManifoldFriction(const BodySim& a, const BodySim& b, const Contact& contact,
                                            const WorldSettings& settings, const PairRows& pair) {
  const Vec3& n = pair.normal;
  const ContactManifold& manifold = contact.manifold;
  const auto count = static_cast<std::size_t>(pair.pointCount);
  const auto first = static_cast<std::size_t>(pair.firstPoint);
  const auto position = [&manifold](int i) { return manifold.points[static_cast<std::size_t>(i)].position; };
  std::array<Vec3, kMaxManifoldPoints> offsets;
  const std::span<Vec3> offsetSpan(offsets.data(), count);
  ManifoldOffsets(pair.pointCount, n, position, offsetSpan);
  for (std::size_t i = 0; i < count; ++i) m_levers[first + i] = offsets[i].norm();
  // Weighted by the impulses the step starts from (none without warm
  // starting: the mean).
  static constexpr std::array<double, kMaxManifoldPoints> kNoLoad{};
  const std::span<const double> load(
      settings.methods.warmStarting ? contact.normalImpulse.data() : kNoLoad.data(), count);
  std::array<double, kMaxManifoldPoints> shareStore;
  const std::span<double> shares(shareStore.data(), count);
  const Vec3 pressure = ManifoldSlipShares(pair.pointCount, load, position, shares);
  const Mat3& invInertiaA = m_bodies.InvInertia(pair.bodyA);
  const Mat3& invInertiaB = m_bodies.InvInertia(pair.bodyB);
  FrictionRow* rows = &m_frictions[static_cast<std::size_t>(pair.firstFriction)];
  for (int k = 0; k < 2; ++k) {
    rows[k] = FrictionRow{};
    rows[k].j =
        MakeRowJacobian(pair.tangent[k], pressure - a.center, pressure - b.center, invInertiaA, invInertiaB);
    rows[k].mass = RowEffectiveMass(rows[k].j, pair.invMassA, pair.invMassB);
  }
  const bool spin = pair.pointCount >= 2;
  if (spin) {
    FrictionRow& row = rows[2];
    row = FrictionRow{};
    row.j.angularA = n;
    row.j.angularB = n;
    row.j.imageA = invInertiaA * n;
    row.j.imageB = invInertiaB * n;
    const double k = n.dot(row.j.imageA) + n.dot(row.j.imageB);
    row.mass = k > 0.0 ? 1.0 / k : 0.0;
  }
  if (!settings.methods.warmStarting) return;
  const ManifoldFrictionImpulses loaded = SumManifoldFriction(
      std::span<const Vec3>(contact.frictionImpulse.data(), count), offsetSpan, shares, n, pair.tangent);
  rows[0].impulse = loaded.slip[0];
  rows[1].impulse = loaded.slip[1];
  if (spin) rows[2].impulse = loaded.spin;
}

// K = J M^-1 J^T of the pair's normal rows, from the rows' precomputed
// angular terms and images, and its least-norm pseudo-inverse
// (dynamics/normal_block.h: a closed form where provably well conditioned,
// else the eigen decomposition), so a symmetric load gets the equal split.
void ContactRowSet::PrepareBlock(const PairRows& pair) {
  const int count = pair.pointCount;
  const NormalRow* rows = &m_normals[static_cast<std::size_t>(pair.firstPoint)];
  const auto jacobian = [rows](int i) -> const RowJacobian& { return rows[i].j; };
  const Eigen::Matrix4d k = NormalBlock(count, pair.invMassA, pair.invMassB, jacobian);
  m_blockInverses[static_cast<std::size_t>(pair.block)] =
      BlockPseudoInverse(k, count, NormalArmsOf(count, jacobian));
}

void ContactRowSet::StoreImpulses(std::span<Contact> contacts) const {
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
      if (pair.manifoldFriction) continue;  // StoreManifoldFriction below
      if (pair.hasFriction) {
        const std::size_t f = static_cast<std::size_t>(pair.firstFriction + 2 * i);
        contact.frictionImpulse[pi] =
            m_frictions[f].impulse * pair.tangent[0] + m_frictions[f + 1].impulse * pair.tangent[1];
      } else {
        contact.frictionImpulse[pi] = Vec3::Zero();
      }
    }
    if (pair.manifoldFriction) StoreManifoldFriction(pair, contact);
  }
}

// Shared out over the points with the slip shares of the normal impulses
// stored beside them (dynamics/manifold_friction.h), their offsets from the arms kept in the
// cold data (an arm differs from the point's position by the body's centre,
// which the mean removes). A timed bounce's point keeps no friction, as
// with per-point rows.
void ContactRowSet::StoreManifoldFriction(const PairRows& pair, Contact& contact) const {
  const PointCold* cold = &m_cold[static_cast<std::size_t>(pair.firstPoint)];
  const FrictionRow* rows = &m_frictions[static_cast<std::size_t>(pair.firstFriction)];
  std::array<Vec3, kMaxManifoldPoints> offsets;
  const std::span<Vec3> offsetSpan(offsets.data(), static_cast<std::size_t>(pair.pointCount));
  ManifoldOffsets(
      pair.pointCount, pair.normal, [cold](int i) { return cold[i].armA; }, offsetSpan);
  ManifoldFrictionImpulses impulses;
  impulses.slip[0] = rows[0].impulse;
  impulses.slip[1] = rows[1].impulse;
  if (pair.pointCount >= 2) impulses.spin = rows[2].impulse;
  const std::span<Vec3> perPoint(contact.frictionImpulse.data(), offsetSpan.size());
  // The shares the next step's rows will read back with: its weights are
  // the normal impulses stored here.
  std::array<double, kMaxManifoldPoints> shares;
  const std::span<double> shareSpan(shares.data(), offsetSpan.size());
  ManifoldSlipShares(
      pair.pointCount, std::span<const double>(contact.normalImpulse.data(), offsetSpan.size()),
      [cold](int i) { return cold[i].armA; }, shareSpan);
  ShareManifoldFriction(impulses, offsetSpan, shareSpan, pair.normal, pair.tangent, perPoint);
  for (int i = 0; i < pair.pointCount; ++i) {
    if (cold[i].timedBounce) perPoint[static_cast<std::size_t>(i)] = Vec3::Zero();
  }
}

}  // namespace talus
