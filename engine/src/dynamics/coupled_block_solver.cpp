// FrictionSolve::CoupledBlock: a face contact's normal rows and its friction
// solved as one block (the derivation is in dynamics/coupled_block_solver.h).
//
// Why. Row by row, a friction impulse at a box's base turns the box (the
// base is below its centre of mass), the normal rows then undo the turn,
// which puts slip back at the base: a stopping cube keeps 0.6 of its slip
// per sweep, and after 5 sweeps at 30 Hz it stops 2.6e-5 m off and rocks.
// Solved together, normals and friction leave the pair at rest in one
// sweep when it sticks. When it slides (or a point lifts) the block is
// refused and the rows run one by one as before; a slide is already near
// exact row by row (every point sits on its bound).
#include "dynamics/coupled_block_solver.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Dense>

#include "dynamics/pair_velocities.h"
#include "dynamics/spd_inverse.h"

namespace talus {

namespace {

// A load whose points all lie within this lever (m) of its centre of
// pressure gives no usable torque about the normal (one point, or points
// that coincide): the spin pattern is dropped, and the per-point rows alone
// decide the spin. A nanometre is far below any manifold's spread and far
// above the round-off of the arms (measured from the centres of mass, so
// independent of where in the world the pair is).
constexpr double kLeastLever = 1e-9;

// The angular part of K = J M^-1 J^T between two rows or patterns.
template <typename P, typename Q>
double AngularCoupling(const P& p, const Q& q) {
  return p.angularA.dot(q.imageA) + p.angularB.dot(q.imageB);
}

// The patterns' weights w_i = lambda_n,i / sum lambda_n from the
// warm-started normal impulses (equal weights when there are none yet: any
// weights give valid patterns, these only decide whose friction takes what
// share, and the acceptance test reads the current normal impulses).
std::array<double, 4> PatternWeights(const NormalRow* normals, int count) {
  double load = 0.0;
  for (int i = 0; i < count; ++i) load += std::max(normals[i].impulse, 0.0);
  std::array<double, 4> weight{};
  for (int i = 0; i < count; ++i) {
    weight[static_cast<std::size_t>(i)] = load > 0.0 ? std::max(normals[i].impulse, 0.0) / load : 1.0 / count;
  }
  return weight;
}

// Slip patterns w_i t_k: r x t is linear in the arm, so their angular parts
// and images are the weighted sums of the rows'. Returns the centre of
// pressure c as an arm from A's centre.
Vec3 SlipPatterns(const std::array<double, 4>& weight, const PointCold* cold, const FrictionRow* rows,
                  int count, RowJacobian (&pattern)[3]) {
  Vec3 centreA = Vec3::Zero();
  for (int i = 0; i < count; ++i) {
    const double w = weight[static_cast<std::size_t>(i)];
    centreA += w * cold[i].armA;
    for (int k = 0; k < 2; ++k) {
      const RowJacobian& j = rows[2 * i + k].j;
      pattern[k].angularA += w * j.angularA;
      pattern[k].angularB += w * j.angularB;
      pattern[k].imageA += w * j.imageA;
      pattern[k].imageB += w * j.imageB;
    }
  }
  return centreA;
}

// Spin pattern w_i (n x (p_i - c)) / S, S = sum w_i |n x (p_i - c)|^2: no
// net force, a unit torque about n through c (exactly so when the points
// lie in the contact plane). Also the points' places in the contact plane
// (coupled.plane) and whether the pattern is used (coupled.spin).
void SpinPattern(const SolverBodies& bodies, const PairRows& pair, const std::array<double, 4>& weight,
                 const PointCold* cold, const Vec3& centreA, RowJacobian& pattern,
                 CoupledBlockRows& coupled) {
  const int count = pair.pointCount;
  const Vec3& n = pair.normal;
  std::array<Vec3, 4> lever{};
  double leverSum = 0.0;
  for (int i = 0; i < count; ++i) {
    const std::size_t si = static_cast<std::size_t>(i);
    const Vec3 offset = cold[i].armA - centreA;
    lever[si] = n.cross(offset);
    leverSum += weight[si] * lever[si].squaredNorm();
    for (int k = 0; k < 2; ++k) coupled.plane(i, k) = offset.dot(pair.tangent[k]);
  }
  coupled.spin = leverSum > kLeastLever * kLeastLever;
  if (coupled.spin) {
    for (int i = 0; i < count; ++i) {
      const std::size_t si = static_cast<std::size_t>(i);
      const double share = weight[si] / leverSum;
      pattern.angularA += share * cold[i].armA.cross(lever[si]);
      pattern.angularB += share * cold[i].armB.cross(lever[si]);
    }
    pattern.imageA = bodies.InvInertia(pair.bodyA) * pattern.angularA;
    pattern.imageB = bodies.InvInertia(pair.bodyB) * pattern.angularB;
    coupled.spin = AngularCoupling(pattern, pattern) > 0.0;  // neither body can turn
  }
  if (!coupled.spin) pattern = RowJacobian{};
}

// K = [Knn Knp; Kpn Kpp], normals n (padded to four), patterns p. Knn's
// pseudo-inverse B is the block inverse. Every column of Knp lies in Knn's
// range (a null vector z of Knn is a normal impulse pattern that moves
// nothing, so it couples to nothing), so the Schur complement
// S = Kpp - Kpn B Knp gives x_p = S^-1 (r_p - (B Knp)^T r_n) and then
// x_n = B r_n - (B Knp) x_p: the velocity change of the full system's
// pseudo-inverse, from a 3x3 factorisation.
void FactorOperator(const PairRows& pair, const NormalRow* normals, const RowJacobian (&pattern)[3],
                    const Eigen::Matrix4d& blockInverse, CoupledBlockRows& coupled) {
  const double linear = pair.invMassA + pair.invMassB;
  const int patterns = coupled.spin ? 3 : 2;
  Eigen::Matrix<double, 4, 3> knp = Eigen::Matrix<double, 4, 3>::Zero();
  for (int i = 0; i < pair.pointCount; ++i) {
    for (int p = 0; p < patterns; ++p) knp(i, p) = AngularCoupling(normals[i].j, pattern[p]);
  }
  Eigen::Matrix3d kpp = Eigen::Matrix3d::Identity();
  for (int p = 0; p < patterns; ++p) {
    for (int q = 0; q < patterns; ++q) {
      kpp(p, q) = (p == q && p < 2 ? linear : 0.0) + AngularCoupling(pattern[p], pattern[q]);
    }
  }
  coupled.blockTimesCoupling = blockInverse * knp;
  const Eigen::Matrix3d schur = kpp - knp.transpose() * coupled.blockTimesCoupling;
  // Not positive definite (or not finite): SpdInverse returns NaNs and the
  // pair keeps the per-point rows.
  coupled.schurInverse = SpdInverse<3>(schur);
  coupled.usable = coupled.schurInverse.allFinite();
}

// The block's velocity step: residuals r_n (normal targets) and r_p (zero
// slip and spin) at the current velocities, and x_p, x_n through the Schur
// complement. False when a result is not finite.
bool BlockStep(const NormalRow* normals, const PairRows& pair, const CoupledBlockRows& coupled,
               const Eigen::Matrix4d& blockInverse, const PairVelocities& v, Eigen::Vector4d& xn,
               Eigen::Vector3d& xp) {
  Eigen::Vector4d rn = Eigen::Vector4d::Zero();
  for (int i = 0; i < pair.pointCount; ++i) rn[i] = normals[i].target - v.Along(pair.normal, normals[i].j);
  Eigen::Vector3d rp = Eigen::Vector3d::Zero();
  for (int p = 0; p < 2; ++p) rp[p] = -v.Along(pair.tangent[p], coupled.pattern[p]);
  if (coupled.spin) rp[2] = -(coupled.pattern[2].angularA.dot(v.wA) - coupled.pattern[2].angularB.dot(v.wB));
  xp = coupled.schurInverse * (rp - coupled.blockTimesCoupling.transpose() * rn);
  xn = blockInverse * rn - coupled.blockTimesCoupling * xp;
  return xp.allFinite() && xn.allFinite();
}

// The friction's total along t1 and t2 and its moment about n through the
// new centre of pressure c' shared among the points in proportion to the
// new normal impulses: force through c', moment as lambda_i (n x (p_i -
// c')) (the share that lets the pair stick longest). False when the load
// sits at one place with a moment to carry, or a point's friction leaves
// its bound.
bool ShareFriction(const FrictionRow* rows, const PairRows& pair, const CoupledBlockRows& coupled,
                   const Eigen::Vector3d& xp, const std::array<double, 4>& normal, double load,
                   std::array<double, 8>& friction) {
  const int count = pair.pointCount;
  std::array<double, 4> share{};  // each point's part of the new load
  for (int i = 0; i < count; ++i)
    share[static_cast<std::size_t>(i)] = normal[static_cast<std::size_t>(i)] / load;
  double force[2] = {xp[0], xp[1]};
  double moment = coupled.spin ? xp[2] : 0.0;
  double centre[2] = {0.0, 0.0};
  for (int i = 0; i < count; ++i) {
    const double f1 = rows[2 * i].impulse;
    const double f2 = rows[2 * i + 1].impulse;
    force[0] += f1;
    force[1] += f2;
    moment += coupled.plane(i, 0) * f2 - coupled.plane(i, 1) * f1;  // (rho x f) . n, t1 x t2 = n
    const double u = share[static_cast<std::size_t>(i)];
    centre[0] += u * coupled.plane(i, 0);
    centre[1] += u * coupled.plane(i, 1);
  }
  double spread = 0.0;
  for (int i = 0; i < count; ++i) {
    const double u = share[static_cast<std::size_t>(i)];
    const double d0 = coupled.plane(i, 0) - centre[0];
    const double d1 = coupled.plane(i, 1) - centre[1];
    spread += u * (d0 * d0 + d1 * d1);
  }
  // The moment about n through c' that the shared torque must carry.
  double twist = 0.0;
  if (coupled.spin) {
    if (!(spread > kLeastLever * kLeastLever)) return false;  // the load cannot carry a torque
    twist = (moment - (centre[0] * force[1] - centre[1] * force[0])) / spread;
  }
  for (int i = 0; i < count; ++i) {
    const std::size_t si = static_cast<std::size_t>(i);
    const double u = share[si];
    // n x (rho - c') in the tangent basis is (-(rho2 - c2), rho1 - c1).
    const double part[2] = {u * (force[0] - twist * (coupled.plane(i, 1) - centre[1])),
                            u * (force[1] + twist * (coupled.plane(i, 0) - centre[0]))};
    const double bound = pair.friction * normal[si];
    for (int k = 0; k < 2; ++k) {
      if (std::abs(part[k]) > bound) return false;
      friction[static_cast<std::size_t>(2 * i + k)] = part[k];
    }
  }
  return true;
}

}  // namespace

void CoupledBlockSolver::Reset(bool enabled, int blocks) {
  m_enabled = enabled;
  m_state.assign(enabled ? static_cast<std::size_t>(blocks) : 0, kUnbuilt);
  m_blocks.resize(enabled ? static_cast<std::size_t>(blocks) : 0);
  m_counts = Counts{};
}

// Once per step, at the pair's first try (its first normal pass of the
// step, before anything changed its impulses, so the same operator as one
// built at Prepare): the patterns from the warm-started normal impulses and
// the solve operator, so that a sweep costs seven dot products, two small
// products and the updates.
CoupledBlockRows CoupledBlockSolver::Build(const ContactRowSet& rows, const PairRows& pair) {
  CoupledBlockRows coupled;
  // The patterns with their images under the inverse inertia (the images
  // only build K; the sweep keeps the angular parts).
  RowJacobian pattern[3];
  const std::size_t first = static_cast<std::size_t>(pair.firstPoint);
  const NormalRow* normals = &rows.Normals()[first];
  const PointCold* cold = &rows.Cold()[first];
  const FrictionRow* frictions = &rows.Frictions()[static_cast<std::size_t>(pair.firstFriction)];
  const std::array<double, 4> weight = PatternWeights(normals, pair.pointCount);
  const Vec3 centreA = SlipPatterns(weight, cold, frictions, pair.pointCount, pattern);
  SpinPattern(rows.Bodies(), pair, weight, cold, centreA, pattern[2], coupled);
  for (int p = 0; p < 3; ++p) coupled.pattern[p] = {pattern[p].angularA, pattern[p].angularB};
  FactorOperator(pair, normals, pattern, rows.BlockInverses()[static_cast<std::size_t>(pair.block)], coupled);
  return coupled;
}

// The first try of a step builds the operator (in place of Prepare, into a
// local): most box-box pairs of a pyramid are refused at their first try
// and not tried again that step, so their operator is never stored, and
// nothing is written at Prepare to be read back from memory here. Any other
// pair keeps it for the step's later sweeps. An operator that is not usable
// counts as refused (it would be refused at every try).
template <bool kTrack>
bool CoupledBlockSolver::Solve(ContactRowSet& rows, const PairRows& pair, double& largest) {
  const std::size_t slot = static_cast<std::size_t>(pair.block);
  State& state = m_state[slot];
  if (state == kRefused) return false;
  if (state != kUnbuilt) return Try<kTrack>(rows, pair, m_blocks[slot], state, largest);
  const CoupledBlockRows coupled = Build(rows, pair);
  if (!coupled.usable) {
    state = kRefused;
    return false;
  }
  const bool accepted = Try<kTrack>(rows, pair, coupled, state, largest);
  if (state != kRefused) m_blocks[slot] = coupled;
  return accepted;
}

// The block fixes what the friction does to the bodies: its total along t1
// and t2 and its moment about n through c (the patterns add x_p to each).
// For points in the contact plane nothing else about it moves the bodies,
// so it is shared anew (ShareFriction). Accepted only if the normals push
// and every point's friction then stays inside its bound (the pair
// sticks). With mu > 0 a pulling normal also fails the bound (it is
// negative); the normal test says why first.
CoupledBlockSolver::Outcome CoupledBlockSolver::SolveBlock(const ContactRowSet& rows, const PairRows& pair,
                                                           const CoupledBlockRows& coupled,
                                                           const PairVelocities& v,
                                                           std::array<double, 4>& normal,
                                                           PointFriction& friction) {
  const NormalRow* normals = &rows.Normals()[static_cast<std::size_t>(pair.firstPoint)];
  Eigen::Vector4d xn;
  Eigen::Vector3d xp;
  const Eigen::Matrix4d& blockInverse = rows.BlockInverses()[static_cast<std::size_t>(pair.block)];
  if (!BlockStep(normals, pair, coupled, blockInverse, v, xn, xp)) return Outcome::kNotSolved;
  double load = 0.0;
  for (int i = 0; i < pair.pointCount; ++i) {
    const std::size_t si = static_cast<std::size_t>(i);
    normal[si] = normals[i].impulse + xn[i];
    if (normal[si] < 0.0) return Outcome::kRefused;
    load += normal[si];
  }
  if (!(load > 0.0)) return Outcome::kNotSolved;
  const FrictionRow* frictions = &rows.Frictions()[static_cast<std::size_t>(pair.firstFriction)];
  return ShareFriction(frictions, pair, coupled, xp, normal, load, friction) ? Outcome::kAccepted
                                                                             : Outcome::kRefused;
}

template <bool kTrack>
bool CoupledBlockSolver::Try(ContactRowSet& rows, const PairRows& pair, const CoupledBlockRows& coupled,
                             State& state, double& largest) {
  state = kUntried;
  SolverVelocity& a = rows.Bodies().Velocity(pair.bodyA);
  SolverVelocity& b = rows.Bodies().Velocity(pair.bodyB);
  PairVelocities v = PairVelocities::Load(a, b);
  std::array<double, 4> normal{};
  PointFriction friction{};
  const Outcome outcome = SolveBlock(rows, pair, coupled, v, normal, friction);
  if (outcome == Outcome::kNotSolved) return false;
  if (outcome == Outcome::kRefused) {
    state = kRefused;
    ++m_counts.refused;
    return false;
  }
  // Applied row by row, so the velocities are exactly what the stored
  // impulses say (next step's warm start starts from them).
  const int count = pair.pointCount;
  NormalRow* normals = &rows.Normals()[static_cast<std::size_t>(pair.firstPoint)];
  FrictionRow* frictions = &rows.Frictions()[static_cast<std::size_t>(pair.firstFriction)];
  ChangeTracker tracker(pair);
  for (int i = 0; i < count; ++i) {
    const double delta = normal[static_cast<std::size_t>(i)] - normals[i].impulse;
    normals[i].impulse = normal[static_cast<std::size_t>(i)];
    if constexpr (kTrack) tracker.Note(delta, normals[i].mass);
    v.Apply(delta, pair.normal, normals[i].j, pair.invMassA, pair.invMassB);
  }
  for (int row = 0; row < 2 * count; ++row) {
    FrictionRow& f = frictions[row];
    const double delta = friction[static_cast<std::size_t>(row)] - f.impulse;
    f.impulse = friction[static_cast<std::size_t>(row)];
    if constexpr (kTrack) tracker.Note(delta, f.mass);
    v.Apply(delta, pair.tangent[row % 2], f.j, pair.invMassA, pair.invMassB);
  }
  v.Store(a, b);
  if constexpr (kTrack) largest = std::max(largest, tracker.largest);
  state = kAccepted;
  ++m_counts.accepted;
  return true;
}

template bool CoupledBlockSolver::Solve<true>(ContactRowSet& rows, const PairRows& pair, double& largest);
template bool CoupledBlockSolver::Solve<false>(ContactRowSet& rows, const PairRows& pair, double& largest);

}  // namespace talus
