// Shock propagation (MethodSettings::shockPropagation): after the velocity
// sweeps, one pass over the contact graph from the immovable bodies up, in
// which each pair's lower body counts as immovable (Guendelman, Bridson and
// Fedkiw, "Nonconvex rigid bodies with stacking", SIGGRAPH 2003, section
// 7; here on the velocity rows). Derivation and measurements:
// docs/dynamics.md, "Shock propagation".
//
// Why. Gauss-Seidel moves load down a chain of contacts at a rate set by
// the masses: a row between a light support and a heavy load changes the
// light body's velocity by the load's share and the heavy one's barely, so
// a slab of M on supports of m needs of the order of M/m sweeps before the
// supports' own contacts carry the slab's weight. Until then the supports
// are driven into the ground; the position bias then pushes them out as
// velocity, and the stack gains energy. With the supports' velocities held,
// the load's rows are a one-body problem whose convergence does not depend
// on the mass ratio, and a resting stack's fixed point (every body still
// at its supports) is reached in one pass from the ground up.
//
// Levels. A body contacts cannot move (static, kinematic, asleep) is level
// 0; a moving body touching a level-k body and none lower is level k + 1
// (breadth first over this step's touching pairs: some point within one
// slop of contact; a speculative pair further apart supports nothing yet
// and is left to the sweeps). A pair belongs to the level of
// its higher body; its body of a lower level is held (zero inverse mass and
// inertia for this pass), two bodies of one level both move. Levels are
// processed in increasing order, each with up to `maxSweeps` sweeps of its
// pairs (normal rows, a pair's as one block with the held body left out
// as the sweeps solve them, then friction rows) until the largest velocity
// change is within `tolerance`. Bodies not connected to an immovable one (a
// floating cluster) have no level and their pairs are not visited: nothing
// holds them, so there is no direction to propagate.
//
// The held body receives no reaction in this pass, so the pass is not a
// momentum exchange: it removes what is left of the approach velocity at
// supports after the sweeps, and the accumulated impulses it adds are warm
// started next step, when both bodies of each pair take them.
#include <algorithm>
#include <limits>

#include "dynamics/contact_solver.h"
#include "dynamics/pair_velocities.h"

namespace talus {

namespace {

constexpr int kNoLevel = std::numeric_limits<int>::max();

template <typename Row>
double HeldRowMass(const Row& row, const ShockSides& s) {
  double k = s.invMassA + s.invMassB;
  if (s.moveA) k += row.j.angularA.dot(row.j.imageA);
  if (s.moveB) k += row.j.angularB.dot(row.j.imageB);
  return k > 0.0 ? 1.0 / k : 0.0;
}

template <typename Row>
void ApplyHeld(PairVelocities& v, double delta, const Vec3& d, const Row& row, const ShockSides& s) {
  const Vec3 impulse = delta * d;
  if (s.moveA) {
    v.vA += s.invMassA * impulse;
    v.wA += delta * row.j.imageA;
  }
  if (s.moveB) {
    v.vB -= s.invMassB * impulse;
    v.wB -= delta * row.j.imageB;
  }
}

}  // namespace

void ContactSolver::AssignShockLevels() {
  const int bodies = m_bodies.Count();
  m_shockLevels.assign(static_cast<std::size_t>(bodies), kNoLevel);
  // Adjacency of the solver bodies through this step's pairs (CSR).
  m_shockAdjStart.assign(static_cast<std::size_t>(bodies) + 1, 0);
  for (std::size_t p = 0; p < m_pairs.size(); ++p) {
    if (m_shockTouching[p] == 0) continue;
    ++m_shockAdjStart[static_cast<std::size_t>(m_pairs[p].bodyA) + 1];
    ++m_shockAdjStart[static_cast<std::size_t>(m_pairs[p].bodyB) + 1];
  }
  for (int i = 0; i < bodies; ++i) {
    m_shockAdjStart[static_cast<std::size_t>(i) + 1] += m_shockAdjStart[static_cast<std::size_t>(i)];
  }
  m_shockAdj.resize(m_pairs.size() * 2);
  m_shockFill.assign(m_shockAdjStart.begin(), m_shockAdjStart.end() - 1);
  for (std::size_t p = 0; p < m_pairs.size(); ++p) {
    if (m_shockTouching[p] == 0) continue;
    const PairRows& pair = m_pairs[p];
    m_shockAdj[static_cast<std::size_t>(m_shockFill[static_cast<std::size_t>(pair.bodyA)]++)] = pair.bodyB;
    m_shockAdj[static_cast<std::size_t>(m_shockFill[static_cast<std::size_t>(pair.bodyB)]++)] = pair.bodyA;
  }
  // Breadth first from every immovable body, in entry order (deterministic).
  m_shockQueue.clear();
  for (int i = 0; i < bodies; ++i) {
    if (!m_bodies.Moves(i)) {
      m_shockLevels[static_cast<std::size_t>(i)] = 0;
      m_shockQueue.push_back(i);
    }
  }
  for (std::size_t head = 0; head < m_shockQueue.size(); ++head) {
    const int body = m_shockQueue[head];
    const int next = m_shockLevels[static_cast<std::size_t>(body)] + 1;
    for (int k = m_shockAdjStart[static_cast<std::size_t>(body)];
         k < m_shockAdjStart[static_cast<std::size_t>(body) + 1]; ++k) {
      const int other = m_shockAdj[static_cast<std::size_t>(k)];
      if (m_shockLevels[static_cast<std::size_t>(other)] != kNoLevel) continue;
      m_shockLevels[static_cast<std::size_t>(other)] = next;
      m_shockQueue.push_back(other);
    }
  }
  // Touching pairs with a level, ordered by it (stable: contact order
  // within one).
  m_shockOrder.clear();
  for (std::size_t p = 0; p < m_pairs.size(); ++p) {
    if (m_shockTouching[p] == 0) continue;
    const PairRows& pair = m_pairs[p];
    const int level = std::max(m_shockLevels[static_cast<std::size_t>(pair.bodyA)],
                               m_shockLevels[static_cast<std::size_t>(pair.bodyB)]);
    if (level != kNoLevel) m_shockOrder.push_back(static_cast<int>(p));
  }
  std::stable_sort(m_shockOrder.begin(), m_shockOrder.end(), [this](int x, int y) {
    return PairLevel(m_pairs[static_cast<std::size_t>(x)]) < PairLevel(m_pairs[static_cast<std::size_t>(y)]);
  });
  KeepLoadedPairs();
}

// Which pairs the pass visits: those where the sweeps cannot be trusted to
// carry the load onto the support. Two cases, each measured against the
// support's own weight this step, m |dv_free| (dv_free: the velocity
// gravity and the applied forces gave it):
// * The load outweighs it. A sweep removes the fraction m / (m + M) of a
//   body M's approach to a support m (the row's effective mass over M's),
//   at least half when M <= m, so ten sweeps leave a thousandth; as M
//   outgrows m the fraction falls towards m / M. Measured as impulse, M
//   dv_free into the support, so a pressed body counts with its press.
// * The warm start is wrong by more than it. In equilibrium last step's
//   impulses cancel what gravity and the forces give a body, so after the
//   warm start it moves as it did at the step's start; a load added or
//   taken away leaves it off by M |v_warmed - v_start|, which the sweeps
//   remove at the same rate. A slab pressed by a large force and then
//   released is launched by impulses sized for the press unless its
//   supports are held.
// A pair so judged is kept, and so is every pair below a kept body down to
// the immovable ones (the support carries the load on to its own
// supports); two bodies of one level share what they carry. Where no load
// outweighs its support and the warm start holds (a settled stack of equal
// boxes) the pass does nothing and costs only the levels.
void ContactSolver::KeepLoadedPairs() {
  m_shockLoaded.assign(m_shockLevels.size(), 0);
  // The impulse body `i` of inverse mass `inverseMass` presses along `into`
  // with this step's free velocity (0 for an immovable body: it presses
  // on nothing).
  const auto load = [this](std::size_t i, double inverseMass, const Vec3& into) {
    return inverseMass > 0.0 ? std::max(0.0, m_shockPush[i].dot(into)) / inverseMass : 0.0;
  };
  // From the top level down: a level's bodies learn what they carry from
  // the level above before their own pairs are decided.
  std::size_t end = m_shockOrder.size();
  std::size_t kept = 0;
  m_shockKeep.assign(m_shockOrder.size(), 0);
  while (end > 0) {
    const int level = PairLevel(m_pairs[static_cast<std::size_t>(m_shockOrder[end - 1])]);
    std::size_t begin = end;
    while (begin > 0 && PairLevel(m_pairs[static_cast<std::size_t>(m_shockOrder[begin - 1])]) == level)
      --begin;
    // Twice over the level: once to share loads along same-level pairs,
    // once more so a pair decided before its neighbour learnt it sees it.
    for (int pass = 0; pass < 2; ++pass) {
      for (std::size_t o = begin; o < end; ++o) {
        const PairRows& pair = m_pairs[static_cast<std::size_t>(m_shockOrder[o])];
        const auto a = static_cast<std::size_t>(pair.bodyA);
        const auto b = static_cast<std::size_t>(pair.bodyB);
        const int levelA = m_shockLevels[a];
        const int levelB = m_shockLevels[b];
        bool keep = false;
        if (levelA == levelB) {
          keep = m_shockLoaded[a] != 0 || m_shockLoaded[b] != 0;
          if (keep) m_shockLoaded[a] = m_shockLoaded[b] = 1;
        } else {
          const bool aUpper = levelA > levelB;
          const std::size_t upper = aUpper ? a : b;
          const std::size_t lower = aUpper ? b : a;
          const double invUpper = aUpper ? pair.invMassA : pair.invMassB;
          const double invLower = aUpper ? pair.invMassB : pair.invMassA;
          // The normal points from B to A: the upper body presses along -n
          // when it is A, along +n when it is B.
          const Vec3 into = aUpper ? Vec3(-pair.normal) : pair.normal;
          const double own = invLower > 0.0 ? m_shockPush[lower].norm() / invLower : 0.0;
          const double offset =
              invUpper > 0.0 ? (m_shockWarmed[upper] - m_shockStart[upper]).norm() / invUpper : 0.0;
          keep = m_shockLoaded[upper] != 0 ||
                 (invLower > 0.0 && (load(upper, invUpper, into) > own || offset > own));
          if (keep) m_shockLoaded[lower] = 1;
        }
        m_shockKeep[o] = keep ? 1 : 0;
      }
    }
    end = begin;
  }
  for (std::size_t o = 0; o < m_shockOrder.size(); ++o) {
    if (m_shockKeep[o] != 0) m_shockOrder[kept++] = m_shockOrder[o];
  }
  m_shockOrder.resize(kept);
}

int ContactSolver::PairLevel(const PairRows& pair) const {
  return std::max(m_shockLevels[static_cast<std::size_t>(pair.bodyA)],
                  m_shockLevels[static_cast<std::size_t>(pair.bodyB)]);
}

// The normal block of the pair at m_shockOrder[order] with its held body
// left out: K over the bodies that move, its pseudo-inverse built at the
// pass's first use. Accepted when no impulse would pull, as in the sweeps'
// block (contact_solver_sweep.cpp); then the rows and `v` are updated.
bool ContactSolver::HeldBlock(std::size_t order, const PairRows& pair, const ShockSides& sides,
                              PairVelocities& v, double& largest) {
  const int count = pair.pointCount;
  NormalRow* rows = &m_normals[static_cast<std::size_t>(pair.firstPoint)];
  if (m_shockBlockBuilt[order] == 0) {
    Eigen::Matrix4d k = Eigen::Matrix4d::Identity();
    for (int i = 0; i < count; ++i) {
      for (int j = 0; j < count; ++j) {
        double kij = sides.invMassA + sides.invMassB;
        if (sides.moveA) kij += rows[i].j.angularA.dot(rows[j].j.imageA);
        if (sides.moveB) kij += rows[i].j.angularB.dot(rows[j].j.imageB);
        k(i, j) = kij;
      }
    }
    m_shockBlocks[order] = BlockPseudoInverse(k, count);
    m_shockBlockBuilt[order] = 1;
  }
  Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
  for (int i = 0; i < count; ++i) rhs[i] = rows[i].target - v.Along(pair.normal, rows[i].j);
  const Eigen::Vector4d delta = m_shockBlocks[order] * rhs;
  for (int i = 0; i < count; ++i) {
    if (rows[i].impulse + delta[i] < 0.0) return false;
  }
  for (int i = 0; i < count; ++i) {
    rows[i].impulse += delta[i];
    const double mass = HeldRowMass(rows[i], sides);
    if (mass > 0.0) largest = std::max(largest, std::abs(delta[i]) / mass);
    ApplyHeld(v, delta[i], pair.normal, rows[i], sides);
  }
  return true;
}

// One sweep over the pairs [begin, end) of m_shockOrder (one level), each
// pair's lower body held. Returns the largest velocity change, m/s.
double ContactSolver::ShockSweep(std::size_t begin, std::size_t end) {
  double largest = 0.0;
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t o = begin; o < end; ++o) {
      const PairRows& pair = m_pairs[static_cast<std::size_t>(m_shockOrder[o])];
      if (pass == 1 && !pair.hasFriction) continue;
      const int levelA = m_shockLevels[static_cast<std::size_t>(pair.bodyA)];
      const int levelB = m_shockLevels[static_cast<std::size_t>(pair.bodyB)];
      ShockSides sides;
      sides.moveA = levelA >= levelB && pair.invMassA > 0.0;
      sides.moveB = levelB >= levelA && pair.invMassB > 0.0;
      sides.invMassA = sides.moveA ? pair.invMassA : 0.0;
      sides.invMassB = sides.moveB ? pair.invMassB : 0.0;
      SolverVelocity& a = m_bodies.Velocity(pair.bodyA);
      SolverVelocity& b = m_bodies.Velocity(pair.bodyB);
      PairVelocities v = PairVelocities::Load(a, b);
      NormalRow* normals = &m_normals[static_cast<std::size_t>(pair.firstPoint)];
      if (pass == 0 && pair.block >= 0 && HeldBlock(o, pair, sides, v, largest)) {
        // The pair's normal rows as one block (as the sweeps solve them:
        // row by row, the first corner takes more of the load and a
        // column leans).
      } else if (pass == 0) {
        for (int i = 0; i < pair.pointCount; ++i) {
          NormalRow& row = normals[i];
          const double mass = HeldRowMass(row, sides);
          const double previous = row.impulse;
          row.impulse = std::max(previous - mass * (v.Along(pair.normal, row.j) - row.target), 0.0);
          const double delta = row.impulse - previous;
          if (mass > 0.0) largest = std::max(largest, std::abs(delta) / mass);
          ApplyHeld(v, delta, pair.normal, row, sides);
        }
      } else {
        FrictionRow* rows = &m_frictions[static_cast<std::size_t>(pair.firstFriction)];
        for (int i = 0; i < pair.pointCount; ++i) {
          const double bound = pair.friction * normals[i].impulse;
          for (int k = 0; k < 2; ++k) {
            FrictionRow& row = rows[2 * i + k];
            const Vec3& t = pair.tangent[k];
            const double mass = HeldRowMass(row, sides);
            const double old = row.impulse;
            row.impulse = std::clamp(old - mass * v.Along(t, row.j), -bound, bound);
            const double delta = row.impulse - old;
            if (mass > 0.0) largest = std::max(largest, std::abs(delta) / mass);
            ApplyHeld(v, delta, t, row, sides);
          }
        }
      }
      v.Store(a, b);
    }
  }
  return largest;
}

int ContactSolver::PropagateShock(int maxSweeps, double tolerance) {
  AssignShockLevels();  // and keeps only the loaded pairs
  m_shockBlocks.resize(m_shockOrder.size());
  m_shockBlockBuilt.assign(m_shockOrder.size(), 0);
  int sweeps = 0;
  std::size_t begin = 0;
  while (begin < m_shockOrder.size()) {
    const int level = PairLevel(m_pairs[static_cast<std::size_t>(m_shockOrder[begin])]);
    std::size_t end = begin;
    while (end < m_shockOrder.size() &&
           PairLevel(m_pairs[static_cast<std::size_t>(m_shockOrder[end])]) == level) {
      ++end;
    }
    for (int s = 0; s < maxSweeps; ++s) {
      ++sweeps;
      if (ShockSweep(begin, end) <= tolerance) break;
    }
    begin = end;
  }
  return sweeps;
}

}  // namespace talus
