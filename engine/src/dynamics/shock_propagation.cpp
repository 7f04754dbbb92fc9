// ShockPropagation (MethodSettings::shockPropagation): after the velocity
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
#include "dynamics/shock_propagation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dynamics/manifold_friction.h"
#include "dynamics/pair_velocities.h"

namespace talus {

namespace {

constexpr int kNoLevel = std::numeric_limits<int>::max();

// The row's effective mass with the held body left out; `linear` false for
// a row with no linear part (the manifold's spin row).
template <typename Row, typename Sides>
double HeldRowMass(const Row& row, const Sides& s, bool linear = true) {
  double k = linear ? s.invMassA + s.invMassB : 0.0;
  if (s.moveA) k += row.j.angularA.dot(row.j.imageA);
  if (s.moveB) k += row.j.angularB.dot(row.j.imageB);
  return k > 0.0 ? 1.0 / k : 0.0;
}

template <typename Row, typename Sides>
void ApplyHeld(PairVelocities& v, double delta, const Vec3& d, const Row& row, const Sides& s) {
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

// Shock propagation's side of SolveManifoldFrictionRows: masses and impulses
// with the held body left out; the spin row has no linear part, so its
// mass has no inverse-mass term.
template <typename Sides>
struct HeldBodyPolicy {
  const Sides& sides;
  double& largest;
  [[nodiscard]] double Mass(const FrictionRow& row, bool linear) const {
    return HeldRowMass(row, sides, linear);
  }
  void Apply(PairVelocities& v, double delta, const Vec3& d, const FrictionRow& row) const {
    ApplyHeld(v, delta, d, row, sides);
  }
  void Note(double velocityChange) const { largest = std::max(largest, velocityChange); }
};

// Whether a pair carries load now (the levels): some point within one slop
// of touching, the band the solver treats as resting. A speculative pair
// whose points are further apart (a body that could reach the other within
// the step) supports nothing yet.
bool Touching(const Contact& contact, double slop) {
  for (int i = 0; i < contact.manifold.pointCount; ++i) {
    if (contact.manifold.points[static_cast<std::size_t>(i)].depth >= -slop) return true;
  }
  return false;
}

}  // namespace

void ShockPropagation::Prepare(std::span<const BodySim> bodies, std::span<const Contact> contacts,
                               const ContactRowSet& rows, double slop) {
  m_touching.clear();
  for (const PairRows& pair : rows.Pairs()) {
    m_touching.push_back(Touching(contacts[static_cast<std::size_t>(pair.contact)], slop) ? 1 : 0);
  }
  // What gravity and the applied forces gave each body this step (the
  // measure of the load a body puts on its supports).
  const SolverBodies& solverBodies = rows.Bodies();
  m_push.resize(static_cast<std::size_t>(solverBodies.Count()));
  m_start.resize(static_cast<std::size_t>(solverBodies.Count()));
  for (int i = 0; i < solverBodies.Count(); ++i) {
    const BodySim& body = bodies[static_cast<std::size_t>(solverBodies.BodyIndex(i))];
    const bool moves = solverBodies.Moves(i);
    m_push[static_cast<std::size_t>(i)] =
        moves ? Vec3(body.freeLinearVelocity - body.startLinearVelocity) : Vec3::Zero();
    m_start[static_cast<std::size_t>(i)] = moves ? body.startLinearVelocity : Vec3::Zero();
  }
}

void ShockPropagation::NoteWarmed(const SolverBodies& bodies) {
  m_warmed.resize(static_cast<std::size_t>(bodies.Count()));
  for (int i = 0; i < bodies.Count(); ++i) m_warmed[static_cast<std::size_t>(i)] = bodies.Velocity(i).v;
}

void ShockPropagation::AssignLevels(const ContactRowSet& rows) {
  BuildAdjacency(rows);
  LevelBodies(rows);
  // Touching pairs with a level, ordered by it (stable: contact order
  // within one).
  const std::span<const PairRows> pairs = rows.Pairs();
  m_order.clear();
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    if (m_touching[p] == 0) continue;
    if (PairLevel(pairs[p]) != kNoLevel) m_order.push_back(static_cast<int>(p));
  }
  std::stable_sort(m_order.begin(), m_order.end(), [this, pairs](int x, int y) {
    return PairLevel(pairs[static_cast<std::size_t>(x)]) < PairLevel(pairs[static_cast<std::size_t>(y)]);
  });
  KeepLoadedPairs(rows);
}

void ShockPropagation::BuildAdjacency(const ContactRowSet& rows) {
  const int bodies = rows.Bodies().Count();
  const std::span<const PairRows> pairs = rows.Pairs();
  m_adjStart.assign(static_cast<std::size_t>(bodies) + 1, 0);
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    if (m_touching[p] == 0) continue;
    ++m_adjStart[static_cast<std::size_t>(pairs[p].bodyA) + 1];
    ++m_adjStart[static_cast<std::size_t>(pairs[p].bodyB) + 1];
  }
  for (int i = 0; i < bodies; ++i) {
    m_adjStart[static_cast<std::size_t>(i) + 1] += m_adjStart[static_cast<std::size_t>(i)];
  }
  m_adj.resize(pairs.size() * 2);
  m_fill.assign(m_adjStart.begin(), m_adjStart.end() - 1);
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    if (m_touching[p] == 0) continue;
    const PairRows& pair = pairs[p];
    m_adj[static_cast<std::size_t>(m_fill[static_cast<std::size_t>(pair.bodyA)]++)] = pair.bodyB;
    m_adj[static_cast<std::size_t>(m_fill[static_cast<std::size_t>(pair.bodyB)]++)] = pair.bodyA;
  }
}

void ShockPropagation::LevelBodies(const ContactRowSet& rows) {
  const int bodies = rows.Bodies().Count();
  m_levels.assign(static_cast<std::size_t>(bodies), kNoLevel);
  // In entry order (deterministic).
  m_queue.clear();
  for (int i = 0; i < bodies; ++i) {
    if (!rows.Bodies().Moves(i)) {
      m_levels[static_cast<std::size_t>(i)] = 0;
      m_queue.push_back(i);
    }
  }
  for (std::size_t head = 0; head < m_queue.size(); ++head) {
    const int body = m_queue[head];
    const int next = m_levels[static_cast<std::size_t>(body)] + 1;
    for (int k = m_adjStart[static_cast<std::size_t>(body)];
         k < m_adjStart[static_cast<std::size_t>(body) + 1]; ++k) {
      const int other = m_adj[static_cast<std::size_t>(k)];
      if (m_levels[static_cast<std::size_t>(other)] != kNoLevel) continue;
      m_levels[static_cast<std::size_t>(other)] = next;
      m_queue.push_back(other);
    }
  }
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
void ShockPropagation::KeepLoadedPairs(const ContactRowSet& rows) {
  const std::span<const PairRows> pairs = rows.Pairs();
  m_loaded.assign(m_levels.size(), 0);
  // From the top level down: a level's bodies learn what they carry from
  // the level above before their own pairs are decided.
  std::size_t end = m_order.size();
  std::size_t kept = 0;
  m_keep.assign(m_order.size(), 0);
  while (end > 0) {
    const int level = PairLevel(pairs[static_cast<std::size_t>(m_order[end - 1])]);
    std::size_t begin = end;
    while (begin > 0 && PairLevel(pairs[static_cast<std::size_t>(m_order[begin - 1])]) == level) --begin;
    // Twice over the level: once to share loads along same-level pairs,
    // once more so a pair decided before its neighbour learnt it sees it.
    for (int pass = 0; pass < 2; ++pass) {
      for (std::size_t o = begin; o < end; ++o) {
        m_keep[o] = KeepPair(pairs[static_cast<std::size_t>(m_order[o])]) ? 1 : 0;
      }
    }
    end = begin;
  }
  for (std::size_t o = 0; o < m_order.size(); ++o) {
    if (m_keep[o] != 0) m_order[kept++] = m_order[o];
  }
  m_order.resize(kept);
}

bool ShockPropagation::KeepPair(const PairRows& pair) {
  // The impulse body `i` of inverse mass `inverseMass` presses along `into`
  // with this step's free velocity (0 for an immovable body: it presses
  // on nothing).
  const auto load = [this](std::size_t i, double inverseMass, const Vec3& into) {
    return inverseMass > 0.0 ? std::max(0.0, m_push[i].dot(into)) / inverseMass : 0.0;
  };
  const auto a = static_cast<std::size_t>(pair.bodyA);
  const auto b = static_cast<std::size_t>(pair.bodyB);
  const int levelA = m_levels[a];
  const int levelB = m_levels[b];
  if (levelA == levelB) {
    const bool keep = m_loaded[a] != 0 || m_loaded[b] != 0;
    if (keep) m_loaded[a] = m_loaded[b] = 1;
    return keep;
  }
  const bool aUpper = levelA > levelB;
  const std::size_t upper = aUpper ? a : b;
  const std::size_t lower = aUpper ? b : a;
  const double invUpper = aUpper ? pair.invMassA : pair.invMassB;
  const double invLower = aUpper ? pair.invMassB : pair.invMassA;
  // The normal points from B to A: the upper body presses along -n
  // when it is A, along +n when it is B.
  const Vec3 into = aUpper ? Vec3(-pair.normal) : pair.normal;
  const double own = invLower > 0.0 ? m_push[lower].norm() / invLower : 0.0;
  const double offset = invUpper > 0.0 ? (m_warmed[upper] - m_start[upper]).norm() / invUpper : 0.0;
  const bool keep =
      m_loaded[upper] != 0 || (invLower > 0.0 && (load(upper, invUpper, into) > own || offset > own));
  if (keep) m_loaded[lower] = 1;
  return keep;
}

int ShockPropagation::PairLevel(const PairRows& pair) const {
  return std::max(m_levels[static_cast<std::size_t>(pair.bodyA)],
                  m_levels[static_cast<std::size_t>(pair.bodyB)]);
}

// A pair's lower body is held; two bodies of one level both move.
ShockPropagation::Sides ShockPropagation::SidesOf(const PairRows& pair) const {
  const int levelA = m_levels[static_cast<std::size_t>(pair.bodyA)];
  const int levelB = m_levels[static_cast<std::size_t>(pair.bodyB)];
  Sides sides;
  sides.moveA = levelA >= levelB && pair.invMassA > 0.0;
  sides.moveB = levelB >= levelA && pair.invMassB > 0.0;
  sides.invMassA = sides.moveA ? pair.invMassA : 0.0;
  sides.invMassB = sides.moveB ? pair.invMassB : 0.0;
  return sides;
}

// The normal block of the pair at m_order[order] with its held body left
// out: K over the bodies that move, its pseudo-inverse built at the pass's
// first use. Accepted when no impulse would pull, as in the sweeps' block
// (sequential_impulse_sweeps.cpp); then the rows and `v` are updated.
bool ShockPropagation::HeldBlock(ContactRowSet& rows, std::size_t order, const PairRows& pair,
                                 const Sides& sides, PairVelocities& v, double& largest) {
  const int count = pair.pointCount;
  NormalRow* normals = &rows.Normals()[static_cast<std::size_t>(pair.firstPoint)];
  if (m_blockBuilt[order] == 0) {
    Eigen::Matrix4d k = Eigen::Matrix4d::Identity();
    for (int i = 0; i < count; ++i) {
      for (int j = 0; j < count; ++j) {
        double kij = sides.invMassA + sides.invMassB;
        if (sides.moveA) kij += normals[i].j.angularA.dot(normals[j].j.imageA);
        if (sides.moveB) kij += normals[i].j.angularB.dot(normals[j].j.imageB);
        k(i, j) = kij;
      }
    }
    const NormalArms arms =
        NormalArmsOf(count, [normals](int i) -> const RowJacobian& { return normals[i].j; });
    m_blocks[order] = BlockPseudoInverse(k, count, arms);
    m_blockBuilt[order] = 1;
  }
  Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
  for (int i = 0; i < count; ++i) rhs[i] = normals[i].target - v.Along(pair.normal, normals[i].j);
  const Eigen::Vector4d delta = m_blocks[order] * rhs;
  for (int i = 0; i < count; ++i) {
    if (normals[i].impulse + delta[i] < 0.0) return false;
  }
  for (int i = 0; i < count; ++i) {
    normals[i].impulse += delta[i];
    const double mass = HeldRowMass(normals[i], sides);
    if (mass > 0.0) largest = std::max(largest, std::abs(delta[i]) / mass);
    ApplyHeld(v, delta[i], pair.normal, normals[i], sides);
  }
  return true;
}

// A pair's normal rows one by one with its held body left out.
void ShockPropagation::HeldNormals(ContactRowSet& rows, const PairRows& pair, const Sides& sides,
                                   PairVelocities& v, double& largest) {
  NormalRow* normals = &rows.Normals()[static_cast<std::size_t>(pair.firstPoint)];
  for (int i = 0; i < pair.pointCount; ++i) {
    NormalRow& row = normals[i];
    const double mass = HeldRowMass(row, sides);
    const double previous = row.impulse;
    row.impulse = std::max(previous - mass * (v.Along(pair.normal, row.j) - row.target), 0.0);
    const double delta = row.impulse - previous;
    if (mass > 0.0) largest = std::max(largest, std::abs(delta) / mass);
    ApplyHeld(v, delta, pair.normal, row, sides);
  }
}

// A pair's friction rows with its held body left out.
void ShockPropagation::HeldFriction(ContactRowSet& rows, const PairRows& pair, const Sides& sides,
                                    PairVelocities& v, double& largest) {
  const NormalRow* normals = &rows.Normals()[static_cast<std::size_t>(pair.firstPoint)];
  FrictionRow* frictions = &rows.Frictions()[static_cast<std::size_t>(pair.firstFriction)];
  if (pair.manifoldFriction) {
    HeldBodyPolicy<Sides> policy{sides, largest};
    const ManifoldLoad loads =
        SumManifoldLoad(pair.pointCount, normals, &rows.Levers()[static_cast<std::size_t>(pair.firstPoint)]);
    SolveManifoldFrictionRows(pair, loads, frictions, v, policy);
    return;
  }
  for (int i = 0; i < pair.pointCount; ++i) {
    const double bound = pair.friction * normals[i].impulse;
    for (int k = 0; k < 2; ++k) {
      FrictionRow& row = frictions[2 * i + k];
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

// One sweep over the pairs [begin, end) of m_order (one level), each
// pair's lower body held: normal rows, a pair's as one block with the held
// body left out (as the sweeps solve them: row by row, the first corner
// takes more of the load and a column leans), then friction rows. Returns
// the largest velocity change, m/s.
double ShockPropagation::Sweep(ContactRowSet& rows, std::size_t begin, std::size_t end) {
  double largest = 0.0;
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t o = begin; o < end; ++o) {
      const PairRows& pair = rows.Pairs()[static_cast<std::size_t>(m_order[o])];
      if (pass == 1 && !pair.hasFriction) continue;
      const Sides sides = SidesOf(pair);
      SolverVelocity& a = rows.Bodies().Velocity(pair.bodyA);
      SolverVelocity& b = rows.Bodies().Velocity(pair.bodyB);
      PairVelocities v = PairVelocities::Load(a, b);
      if (pass == 1) {
        HeldFriction(rows, pair, sides, v, largest);
      } else if (pair.block < 0 || !HeldBlock(rows, o, pair, sides, v, largest)) {
        HeldNormals(rows, pair, sides, v, largest);
      }
      v.Store(a, b);
    }
  }
  return largest;
}

int ShockPropagation::Propagate(ContactRowSet& rows, int maxSweeps, double tolerance) {
  AssignLevels(rows);  // and keeps only the loaded pairs
  m_blocks.resize(m_order.size());
  m_blockBuilt.assign(m_order.size(), 0);
  const std::span<const PairRows> pairs = rows.Pairs();
  int sweeps = 0;
  std::size_t begin = 0;
  while (begin < m_order.size()) {
    const int level = PairLevel(pairs[static_cast<std::size_t>(m_order[begin])]);
    std::size_t end = begin;
    while (end < m_order.size() && PairLevel(pairs[static_cast<std::size_t>(m_order[end])]) == level) ++end;
    for (int s = 0; s < maxSweeps; ++s) {
      ++sweeps;
      if (Sweep(rows, begin, end) <= tolerance) break;
    }
    begin = end;
  }
  return sweeps;
}

}  // namespace talus
