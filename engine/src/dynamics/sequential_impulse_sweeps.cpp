// The velocity sweeps of the scalar contact solver: projected Gauss-Seidel
// over the rows ContactRowSet built (derivations in
// dynamics/sequential_impulse_sweeps.h), the block solve of a pair's normal
// rows, and the warm start.
//
// Every row reads and writes the two solver bodies of its pair, loaded into
// locals once per pass over the pair and stored at its end. A row along
// direction d is two dot products for Cdot = d.(vA - vB) + (rA x d).wA -
// (rB x d).wB and four axpys for the update, with the angular terms and
// their images under the inverse inertia precomputed (Catto's Box2D v3 and
// Bullet's btSolverConstraint do the same): no cross product and no 3x3
// product per row per sweep. Bodies contacts cannot move have zero inverse
// mass and zero images, so the update adds exactly zero to them.
//
// The change tracking the extra sweeps need (ChangeTracker) is compiled into
// a second instance of each pass (kTrack) so the fixed sweeps pay nothing.
#include "dynamics/sequential_impulse_sweeps.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "dynamics/manifold_friction.h"
#include "dynamics/pair_velocities.h"

namespace talus {

void SequentialImpulseSweeps::WarmStart(ContactRowSet& rows) {
  for (const PairRows& pair : rows.Pairs()) WarmStartPair(rows, pair);
}

void SequentialImpulseSweeps::WarmStartPair(ContactRowSet& rows, const PairRows& pair) {
  SolverVelocity& a = rows.Bodies().Velocity(pair.bodyA);
  SolverVelocity& b = rows.Bodies().Velocity(pair.bodyB);
  for (int i = 0; i < pair.pointCount; ++i) {
    const NormalRow& row = rows.Normals()[static_cast<std::size_t>(pair.firstPoint + i)];
    Vec3 impulse = row.impulse * pair.normal;
    Vec3 turnA = row.impulse * row.j.imageA;
    Vec3 turnB = row.impulse * row.j.imageB;
    if (pair.hasFriction && !pair.manifoldFriction) {
      for (int k = 0; k < 2; ++k) {
        const FrictionRow& f = rows.Frictions()[static_cast<std::size_t>(pair.firstFriction + 2 * i + k)];
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
  if (!pair.manifoldFriction) return;
  // The manifold's rows: slip at the centre, spin (no linear part).
  const FrictionRow* rowsOfPair = &rows.Frictions()[static_cast<std::size_t>(pair.firstFriction)];
  for (int k = 0; k < ManifoldFrictionRowCount(pair.pointCount); ++k) {
    const FrictionRow& f = rowsOfPair[k];
    if (k < 2) {
      a.v += pair.invMassA * f.impulse * pair.tangent[k];
      b.v -= pair.invMassB * f.impulse * pair.tangent[k];
    }
    a.w += f.impulse * f.j.imageA;
    b.w -= f.impulse * f.j.imageB;
  }
}

namespace {

// The sweeps' side of SolveManifoldFrictionRows: the rows' own masses, both
// bodies free, the change noted for the extra sweeps' stop test.
struct FreeBodiesPolicy {
  const PairRows& pair;
  ChangeTracker& change;
  [[nodiscard]] double Mass(const FrictionRow& row, bool /*linear*/) const { return row.mass; }
  void Apply(PairVelocities& v, double delta, const Vec3& d, const FrictionRow& row) const {
    v.Apply(delta, d, row.j, pair.invMassA, pair.invMassB);
  }
  void Note(double velocityChange) const {
    if (change.active) change.largest = std::max(change.largest, velocityChange);
  }
};

}  // namespace

template <bool kTrack>
bool SequentialImpulseSweeps::SolveNormalBlock(ContactRowSet& rows, const PairRows& pair) {
  SolverVelocity& a = rows.Bodies().Velocity(pair.bodyA);
  SolverVelocity& b = rows.Bodies().Velocity(pair.bodyB);
  NormalRow* normals = &rows.Normals()[static_cast<std::size_t>(pair.firstPoint)];
  const Vec3& n = pair.normal;
  const Vec3 dv = a.v - b.v;
  const double vn0 = n.dot(dv);
  Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
  Eigen::Vector4d lambda = Eigen::Vector4d::Zero();
  for (int i = 0; i < pair.pointCount; ++i) {
    const double vn = vn0 + normals[i].j.angularA.dot(a.w) - normals[i].j.angularB.dot(b.w);
    rhs[i] = normals[i].target - vn;
    lambda[i] = normals[i].impulse;
  }
  const Eigen::Vector4d delta = rows.BlockInverses()[static_cast<std::size_t>(pair.block)] * rhs;
  for (int i = 0; i < pair.pointCount; ++i) {
    if (lambda[i] + delta[i] < 0.0) return false;
  }
  PairVelocities v = PairVelocities::Load(a, b);
  ChangeTracker change(pair);
  for (int i = 0; i < pair.pointCount; ++i) {
    NormalRow& row = normals[i];
    row.impulse = lambda[i] + delta[i];
    if constexpr (kTrack) change.Note(delta[i], row.mass);
    v.Apply(delta[i], n, row.j, pair.invMassA, pair.invMassB);
  }
  v.Store(a, b);
  if constexpr (kTrack) m_largestChange = std::max(m_largestChange, change.largest);
  return true;
}

// The normal rows of one pair (SolvePairNormals), then, for a pair with
// manifold friction, the loads its friction rows will read: summed here,
// from the rows this pass has just written (still in cache), instead of by
// the friction pass, which would fetch every point's normal row again
// (the hottest part of the manifold friction rows on the pyramid:
// docs/bench-scenes.md, "Throughput, 2026-12-07"). The friction pass of the same sweep
// follows every pair's normal pass and nothing between them changes a
// pair's normal impulses, so the loads are the same bits it would sum.
template <bool kTrack>
void SequentialImpulseSweeps::SolveNormals(ContactRowSet& rows, CoupledBlockSolver& coupled,
                                           const PairRows& pair) {
  SolvePairNormals<kTrack>(rows, coupled, pair);
  if (!pair.manifoldFriction || !pair.hasFriction) return;
  const auto first = static_cast<std::size_t>(pair.firstPoint);
  m_loads[PairIndex(rows, pair)] =
      SumManifoldLoad(pair.pointCount, &rows.Normals()[first], &rows.Levers()[first]);
}

// The normal rows of one pair: the coupled block or the normal block when
// they apply and accept, else row by row, accumulated impulse clamped to
// [0, inf).
template <bool kTrack>
void SequentialImpulseSweeps::SolvePairNormals(ContactRowSet& rows, CoupledBlockSolver& coupled,
                                               const PairRows& pair) {
  if (coupled.Applies(pair) && coupled.Solve<kTrack>(rows, pair, m_largestChange)) return;
  if (pair.block >= 0 && SolveNormalBlock<kTrack>(rows, pair)) return;
  SolverVelocity& a = rows.Bodies().Velocity(pair.bodyA);
  SolverVelocity& b = rows.Bodies().Velocity(pair.bodyB);
  PairVelocities v = PairVelocities::Load(a, b);
  NormalRow* normals = &rows.Normals()[static_cast<std::size_t>(pair.firstPoint)];
  const Vec3& n = pair.normal;
  ChangeTracker change(pair);
  for (int i = 0; i < pair.pointCount; ++i) {
    NormalRow& row = normals[i];
    const double vn = v.Along(n, row.j);
    const double previous = row.impulse;
    row.impulse = std::max(previous - row.mass * (vn - row.target), 0.0);
    const double delta = row.impulse - previous;
    if constexpr (kTrack) change.Note(delta, row.mass);
    v.Apply(delta, n, row.j, pair.invMassA, pair.invMassB);
  }
  v.Store(a, b);
  if constexpr (kTrack) m_largestChange = std::max(m_largestChange, change.largest);
}

// The friction rows of one pair, each bounded by mu times its point's
// current normal impulse.
template <bool kTrack>
void SequentialImpulseSweeps::SolveFriction(ContactRowSet& rows, const CoupledBlockSolver& coupled,
                                            const PairRows& pair) {
  if (coupled.SolvedFriction(pair)) return;  // the coupled block solved this pair's friction in this sweep
  SolverVelocity& a = rows.Bodies().Velocity(pair.bodyA);
  SolverVelocity& b = rows.Bodies().Velocity(pair.bodyB);
  PairVelocities v = PairVelocities::Load(a, b);
  const NormalRow* normals = &rows.Normals()[static_cast<std::size_t>(pair.firstPoint)];
  FrictionRow* frictions = &rows.Frictions()[static_cast<std::size_t>(pair.firstFriction)];
  ChangeTracker change(pair);
  if (pair.manifoldFriction) {
    FreeBodiesPolicy policy{pair, change};
    SolveManifoldFrictionRows(pair, m_loads[PairIndex(rows, pair)], frictions, v, policy);
    v.Store(a, b);
    if constexpr (kTrack) m_largestChange = std::max(m_largestChange, change.largest);
    return;
  }
  for (int i = 0; i < pair.pointCount; ++i) {
    const double bound = pair.friction * normals[i].impulse;
    for (int k = 0; k < 2; ++k) {
      FrictionRow& row = frictions[2 * i + k];
      const Vec3& t = pair.tangent[k];
      const double vt = v.Along(t, row.j);
      const double old = row.impulse;
      row.impulse = std::clamp(old - row.mass * vt, -bound, bound);
      const double delta = row.impulse - old;
      if constexpr (kTrack) change.Note(delta, row.mass);
      v.Apply(delta, t, row.j, pair.invMassA, pair.invMassB);
    }
  }
  v.Store(a, b);
  if constexpr (kTrack) m_largestChange = std::max(m_largestChange, change.largest);
}

template <bool kTrack>
void SequentialImpulseSweeps::SweepAll(ContactRowSet& rows, CoupledBlockSolver& coupled) {
  for (const PairRows& pair : rows.Pairs()) SolveNormals<kTrack>(rows, coupled, pair);
  for (const PairRows& pair : rows.Pairs()) {
    if (pair.hasFriction) SolveFriction<kTrack>(rows, coupled, pair);
  }
}

double SequentialImpulseSweeps::Sweep(ContactRowSet& rows, CoupledBlockSolver& coupled, bool track) {
  m_largestChange = 0.0;
  m_loads.resize(rows.Pairs().size());
  if (track) {
    SweepAll<true>(rows, coupled);
  } else {
    SweepAll<false>(rows, coupled);
  }
  return m_largestChange;
}

template <bool kTrack>
void SequentialImpulseSweeps::SolvePairList(ContactRowSet& rows, CoupledBlockSolver& coupled,
                                            std::span<const int> pairs, bool friction) {
  for (const int p : pairs) {
    const PairRows& pair = rows.Pairs()[static_cast<std::size_t>(p)];
    if (!friction) {
      SolveNormals<kTrack>(rows, coupled, pair);
    } else if (pair.hasFriction) {
      SolveFriction<kTrack>(rows, coupled, pair);
    }
  }
}

double SequentialImpulseSweeps::SolvePairs(ContactRowSet& rows, CoupledBlockSolver& coupled,
                                           std::span<const int> pairs, bool friction, bool track) {
  m_largestChange = 0.0;
  m_loads.resize(rows.Pairs().size());
  if (track) {
    SolvePairList<true>(rows, coupled, pairs, friction);
  } else {
    SolvePairList<false>(rows, coupled, pairs, friction);
  }
  return m_largestChange;
}

}  // namespace talus
