// The velocity sweeps of the contact solver: projected Gauss-Seidel over the
// rows Prepare built (derivations in dynamics/contact_solver.h), and the
// block solve of a pair's normal rows.
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
#include <algorithm>
#include <atomic>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "dynamics/contact_solver.h"
#include "dynamics/pair_velocities.h"

namespace talus {

namespace {

// Bundles (four pairs each) per chunk of a colour's pass: a bundle's rows
// are about a microsecond, so a chunk is well above the cost of claiming
// it, and the smaller colours still split across two threads.
constexpr int kSweepBundleGrain = 8;

}  // namespace

// K = J M^-1 J^T of the pair's normal rows, from the rows' precomputed
// angular terms and images, and its pseudo-inverse from an eigen
// decomposition: eigenvalues below 1e-9 of the largest count as zero (four
// coplanar points give rank 3; K is padded with the identity below four
// points), so a symmetric load gets the least-norm, equal split.
//
// A closed form (deflating the null vector of the four points' affine
// dependency, then a 4x4 inverse; 1.7x faster Prepare) agreed with this to
// 1e-8 but is not used: pyramid 15's drift is a lottery at round-off level
// (this same matrix scaled by 1 +- 1e-14 gives 1.5 mm or 1.2 cm; the closed
// form drew 11 cm, past the 5 cm gate). See docs/dynamics.md.
void ContactSolver::PrepareBlock(PairRows& pair) {
  const int count = pair.pointCount;
  const NormalRow* rows = &m_normals[static_cast<std::size_t>(pair.firstPoint)];
  Eigen::Matrix4d k = Eigen::Matrix4d::Identity();
  for (int i = 0; i < count; ++i) {
    for (int j = 0; j < count; ++j) {
      k(i, j) = pair.invMassA + pair.invMassB + rows[i].j.angularA.dot(rows[j].j.imageA) +
                rows[i].j.angularB.dot(rows[j].j.imageB);
    }
  }
  m_blockInverses[static_cast<std::size_t>(pair.block)] = BlockPseudoInverse(k, count);
}

Eigen::Matrix4d ContactSolver::BlockPseudoInverse(const Eigen::Matrix4d& k, int count) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(k);
  const Eigen::Vector4d values = eigen.eigenvalues();
  const double largest = values.cwiseAbs().maxCoeff();
  Eigen::Vector4d inverse = Eigen::Vector4d::Zero();
  for (int i = 0; i < 4; ++i) {
    if (values[i] > 1e-9 * largest) inverse[i] = 1.0 / values[i];
  }
  Eigen::Matrix4d blockInverse =
      eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
  for (int i = count; i < 4; ++i) {
    blockInverse.row(i).setZero();
    blockInverse.col(i).setZero();
  }
  return blockInverse;
}

template <bool kTrack>
bool ContactSolver::SolveNormalBlock(const PairRows& pair) {
  SolverVelocity& a = m_bodies.Velocity(pair.bodyA);
  SolverVelocity& b = m_bodies.Velocity(pair.bodyB);
  NormalRow* rows = &m_normals[static_cast<std::size_t>(pair.firstPoint)];
  const Vec3& n = pair.normal;
  const Vec3 dv = a.v - b.v;
  const double vn0 = n.dot(dv);
  Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
  Eigen::Vector4d lambda = Eigen::Vector4d::Zero();
  for (int i = 0; i < pair.pointCount; ++i) {
    const double vn = vn0 + rows[i].j.angularA.dot(a.w) - rows[i].j.angularB.dot(b.w);
    rhs[i] = rows[i].target - vn;
    lambda[i] = rows[i].impulse;
  }
  const Eigen::Vector4d delta = m_blockInverses[static_cast<std::size_t>(pair.block)] * rhs;
  for (int i = 0; i < pair.pointCount; ++i) {
    if (lambda[i] + delta[i] < 0.0) return false;
  }
  PairVelocities v = PairVelocities::Load(a, b);
  ChangeTracker change(pair);
  for (int i = 0; i < pair.pointCount; ++i) {
    NormalRow& row = rows[i];
    row.impulse = lambda[i] + delta[i];
    if constexpr (kTrack) change.Note(delta[i], row.mass);
    v.Apply(delta[i], n, row.j, pair.invMassA, pair.invMassB);
  }
  v.Store(a, b);
  if constexpr (kTrack) m_largestChange = std::max(m_largestChange, change.largest);
  return true;
}

// The normal rows of one pair: accumulated impulse clamped to [0, inf).
template <bool kTrack>
void ContactSolver::SolveNormals(const PairRows& pair) {
  if (UsesJointBlock(pair) && SolveJointBlock<kTrack>(pair)) return;
  if (pair.block >= 0 && SolveNormalBlock<kTrack>(pair)) return;
  SolverVelocity& a = m_bodies.Velocity(pair.bodyA);
  SolverVelocity& b = m_bodies.Velocity(pair.bodyB);
  PairVelocities v = PairVelocities::Load(a, b);
  NormalRow* rows = &m_normals[static_cast<std::size_t>(pair.firstPoint)];
  const Vec3& n = pair.normal;
  ChangeTracker change(pair);
  for (int i = 0; i < pair.pointCount; ++i) {
    NormalRow& row = rows[i];
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
void ContactSolver::SolveFriction(const PairRows& pair) {
  if (UsesJointBlock(pair) && m_jointState[static_cast<std::size_t>(pair.block)] == kJointAccepted) {
    return;  // the joint block solved this pair's friction in this sweep
  }
  SolverVelocity& a = m_bodies.Velocity(pair.bodyA);
  SolverVelocity& b = m_bodies.Velocity(pair.bodyB);
  PairVelocities v = PairVelocities::Load(a, b);
  const NormalRow* normals = &m_normals[static_cast<std::size_t>(pair.firstPoint)];
  FrictionRow* rows = &m_frictions[static_cast<std::size_t>(pair.firstFriction)];
  ChangeTracker change(pair);
  for (int i = 0; i < pair.pointCount; ++i) {
    const double bound = pair.friction * normals[i].impulse;
    for (int k = 0; k < 2; ++k) {
      FrictionRow& row = rows[2 * i + k];
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
void ContactSolver::Sweep() {
  for (const PairRows& pair : m_pairs) SolveNormals<kTrack>(pair);
  for (const PairRows& pair : m_pairs) {
    if (pair.hasFriction) SolveFriction<kTrack>(pair);
  }
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
//
// Coloured (ContactOrder::ByColour), the same sweeps visit each
// colour's pairs four at a time, then the overflow pairs one by one; the
// impulses go back to the scalar rows at the end, where the position
// passes and StoreImpulses read them.
int ContactSolver::SolveVelocities(int minIterations, int maxIterations, double tolerance) {
  const auto sweep = [this](bool track) {
    m_largestChange = 0.0;
    if (m_useWide) {
      m_largestChange = std::max(m_largestChange, SweepsWide(1, track));
    } else if (track) {
      Sweep<true>();
    } else {
      Sweep<false>();
    }
    return m_largestChange;
  };
  if (m_shock) {
    // Shock propagation reads how far the warm start left each body from
    // where the step began (KeepLoadedPairs).
    m_shockWarmed.resize(static_cast<std::size_t>(m_bodies.Count()));
    for (int i = 0; i < m_bodies.Count(); ++i)
      m_shockWarmed[static_cast<std::size_t>(i)] = m_bodies.Velocity(i).v;
  }
  int sweeps = 0;
  if (m_useWide && minIterations > 0) {
    // The untracked sweeps need no result between them: one chain.
    SweepsWide(minIterations, false);
    sweeps = minIterations;
  }
  for (; sweeps < minIterations; ++sweeps) sweep(false);
  if (m_newPairs != 0) {
    for (; sweeps < maxIterations;) {
      ++sweeps;
      if (sweep(true) <= tolerance) break;
    }
  }
  if (m_useWide) m_wide.Unpack(m_pairs, m_normals, m_frictions, m_runner);
  m_shockSweeps = m_shock ? PropagateShock(minIterations, tolerance) : 0;
  return sweeps;
}

// Each sweep is 2 (colours + 1) phases: the colours' normal rows, the
// overflow pairs' normal rows (one chunk: they run one by one, in order),
// then the same for the friction rows. A colour's bundles are split into
// chunks of kSweepBundleGrain; the phases of all `sweeps` sweeps are one
// chain, so the threads meet once per phase on finished chunks instead of
// being handed a new job per colour.
double ContactSolver::SweepsWide(int sweeps, bool track) {
  const int colours = m_wide.ColourCount();
  const int perSweep = 2 * (colours + 1);
  const int overflow = m_wide.OverflowPairs().empty() ? 0 : 1;
  std::vector<JobPhase>& phases = m_phases;
  phases.clear();
  for (int s = 0; s < sweeps; ++s) {
    for (int pass = 0; pass < 2; ++pass) {
      for (int colour = 0; colour < colours; ++colour) {
        phases.push_back({.count = m_wide.BundleCount(colour), .grain = kSweepBundleGrain});
      }
      phases.push_back({.count = overflow, .grain = 1});
    }
  }
  std::atomic<double> largest{0.0};
  RunPhasesWith(m_runner, phases, [&](int phase, int begin, int end) {
    const int inSweep = phase % perSweep;
    const bool friction = inSweep > colours;
    const int colour = friction ? inSweep - colours - 1 : inSweep;
    double mine = 0.0;
    if (colour < colours) {
      mine = friction ? m_wide.SolveFrictionRange(m_bodies, colour, begin, end, track)
                      : m_wide.SolveNormalRange(m_bodies, colour, begin, end, track);
    } else {
      // The overflow pairs one by one with the scalar passes (their own
      // tracking goes through m_largestChange; the phases before and after
      // this one's single chunk order every other access to it).
      m_largestChange = 0.0;
      for (const int p : m_wide.OverflowPairs()) {
        const PairRows& pair = m_pairs[static_cast<std::size_t>(p)];
        if (friction && !pair.hasFriction) continue;
        if (friction) {
          if (track) {
            SolveFriction<true>(pair);
          } else {
            SolveFriction<false>(pair);
          }
        } else if (track) {
          SolveNormals<true>(pair);
        } else {
          SolveNormals<false>(pair);
        }
      }
      mine = m_largestChange;
    }
    double seen = largest.load(std::memory_order_relaxed);
    while (mine > seen && !largest.compare_exchange_weak(seen, mine, std::memory_order_relaxed)) {
    }
  });
  return largest.load(std::memory_order_relaxed);
}

}  // namespace talus
