// FrictionSolve::CoupledBlock: a face contact's normal rows and its friction
// solved as one block (the derivation is in dynamics/contact_solver.h).
//
// Why. Row by row, a friction impulse at a box's base turns the box (the
// base is below its centre of mass), the normal rows then undo the turn,
// which puts slip back at the base: a stopping cube keeps 0.6 of its slip
// per sweep, and after 5 sweeps at 30 Hz it stops 2.6e-5 m off and rocks.
// Solved together, normals and friction leave the pair at rest in one
// sweep when it sticks. When it slides (or a point lifts) the block is
// refused and the rows run one by one as before; a slide is already near
// exact row by row (every point sits on its bound).
#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Dense>

#include "dynamics/contact_solver.h"
#include "dynamics/pair_velocities.h"

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

}  // namespace

// Once per step, at the pair's first try (its first normal pass of the
// step, before anything changed its impulses, so the same operator as one
// built at Prepare): the patterns from the warm-started normal impulses
// (equal weights when there are none yet: any weights give valid patterns,
// these only decide whose friction takes what share, and the acceptance
// test reads the current normal impulses), and the solve operator, so that
// a sweep costs seven dot products, two small products and the updates.
JointBlockRows ContactSolver::BuildJointBlock(const PairRows& pair) const {
  JointBlockRows joint;
  // The patterns with their images under the inverse inertia (the images
  // only build K; the sweep keeps the angular parts).
  RowJacobian pattern[3];
  const int count = pair.pointCount;
  const std::size_t first = static_cast<std::size_t>(pair.firstPoint);
  const NormalRow* normals = &m_normals[first];
  const PointCold* cold = &m_cold[first];
  const FrictionRow* rows = &m_frictions[static_cast<std::size_t>(pair.firstFriction)];
  double load = 0.0;
  for (int i = 0; i < count; ++i) load += std::max(normals[i].impulse, 0.0);
  std::array<double, 4> weight{};
  for (int i = 0; i < count; ++i) {
    weight[static_cast<std::size_t>(i)] = load > 0.0 ? std::max(normals[i].impulse, 0.0) / load : 1.0 / count;
  }
  // Slip patterns w_i t_k: r x t is linear in the arm, so their angular
  // parts and images are the weighted sums of the rows'.
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
  // Spin pattern w_i (n x (p_i - c)) / S, S = sum w_i |n x (p_i - c)|^2: no
  // net force, a unit torque about n through c (exactly so when the points
  // lie in the contact plane).
  const Vec3& n = pair.normal;
  std::array<Vec3, 4> lever{};
  double leverSum = 0.0;
  for (int i = 0; i < count; ++i) {
    const std::size_t si = static_cast<std::size_t>(i);
    const Vec3 offset = cold[i].armA - centreA;
    lever[si] = n.cross(offset);
    leverSum += weight[si] * lever[si].squaredNorm();
    for (int k = 0; k < 2; ++k) joint.plane(i, k) = offset.dot(pair.tangent[k]);
  }
  joint.spin = leverSum > kLeastLever * kLeastLever;
  if (joint.spin) {
    for (int i = 0; i < count; ++i) {
      const std::size_t si = static_cast<std::size_t>(i);
      const double share = weight[si] / leverSum;
      pattern[2].angularA += share * cold[i].armA.cross(lever[si]);
      pattern[2].angularB += share * cold[i].armB.cross(lever[si]);
    }
    pattern[2].imageA = m_bodies.InvInertia(pair.bodyA) * pattern[2].angularA;
    pattern[2].imageB = m_bodies.InvInertia(pair.bodyB) * pattern[2].angularB;
    joint.spin = AngularCoupling(pattern[2], pattern[2]) > 0.0;  // neither body can turn
  }
  if (!joint.spin) pattern[2] = RowJacobian{};
  for (int p = 0; p < 3; ++p) joint.pattern[p] = {pattern[p].angularA, pattern[p].angularB};
  // K = [Knn Knp; Kpn Kpp], normals n (padded to four), patterns p. Knn's
  // pseudo-inverse B is the block inverse. Every column of Knp lies in
  // Knn's range (a null vector z of Knn is a normal impulse pattern that
  // moves nothing, so it couples to nothing), so the Schur complement
  // S = Kpp - Kpn B Knp gives x_p = S^-1 (r_p - (B Knp)^T r_n) and then
  // x_n = B r_n - (B Knp) x_p: the velocity change of the full system's
  // pseudo-inverse, from a 3x3 factorisation.
  const double linear = pair.invMassA + pair.invMassB;
  const int patterns = joint.spin ? 3 : 2;
  Eigen::Matrix<double, 4, 3> knp = Eigen::Matrix<double, 4, 3>::Zero();
  for (int i = 0; i < count; ++i) {
    for (int p = 0; p < patterns; ++p) knp(i, p) = AngularCoupling(normals[i].j, pattern[p]);
  }
  Eigen::Matrix3d kpp = Eigen::Matrix3d::Identity();
  for (int p = 0; p < patterns; ++p) {
    for (int q = 0; q < patterns; ++q) {
      kpp(p, q) = (p == q && p < 2 ? linear : 0.0) + AngularCoupling(pattern[p], pattern[q]);
    }
  }
  const Eigen::Matrix4d& blockInverse = m_blockInverses[static_cast<std::size_t>(pair.block)];
  joint.blockTimesCoupling = blockInverse * knp;
  const Eigen::Matrix3d schur = kpp - knp.transpose() * joint.blockTimesCoupling;
  const Eigen::LDLT<Eigen::Matrix3d> factor(schur);
  joint.usable = factor.info() == Eigen::Success && factor.isPositive() && schur.allFinite();
  if (joint.usable) {
    joint.schurInverse = factor.solve(Eigen::Matrix3d::Identity());
    joint.usable = joint.schurInverse.allFinite();
  }
  return joint;
}

// The first try of a step builds the operator (in place of Prepare, into a
// local): most box-box pairs of a pyramid are refused at their first try
// and not tried again that step, so their operator is never stored, and
// nothing is written at Prepare to be read back from memory here. Any other
// pair keeps it for the step's later sweeps. An operator that is not usable
// counts as refused (it would be refused at every try).
template <bool kTrack>
bool ContactSolver::SolveJointBlock(const PairRows& pair) {
  const std::size_t slot = static_cast<std::size_t>(pair.block);
  JointState& state = m_jointState[slot];
  if (state == kJointRefused) return false;
  if (state != kJointUnbuilt) return TryJointBlock<kTrack>(pair, m_jointBlocks[slot], state);
  const JointBlockRows joint = BuildJointBlock(pair);
  if (!joint.usable) {
    state = kJointRefused;
    return false;
  }
  const bool accepted = TryJointBlock<kTrack>(pair, joint, state);
  if (state != kJointRefused) m_jointBlocks[slot] = joint;
  return accepted;
}

template <bool kTrack>
bool ContactSolver::TryJointBlock(const PairRows& pair, const JointBlockRows& joint, JointState& state) {
  state = kJointUntried;
  const int count = pair.pointCount;
  const std::size_t first = static_cast<std::size_t>(pair.firstPoint);
  NormalRow* normals = &m_normals[first];
  FrictionRow* rows = &m_frictions[static_cast<std::size_t>(pair.firstFriction)];
  SolverVelocity& a = m_bodies.Velocity(pair.bodyA);
  SolverVelocity& b = m_bodies.Velocity(pair.bodyB);
  PairVelocities v = PairVelocities::Load(a, b);
  const Vec3& n = pair.normal;
  Eigen::Vector4d rn = Eigen::Vector4d::Zero();
  for (int i = 0; i < count; ++i) rn[i] = normals[i].target - v.Along(n, normals[i].j);
  Eigen::Vector3d rp = Eigen::Vector3d::Zero();
  for (int p = 0; p < 2; ++p) rp[p] = -v.Along(pair.tangent[p], joint.pattern[p]);
  if (joint.spin) rp[2] = -(joint.pattern[2].angularA.dot(v.wA) - joint.pattern[2].angularB.dot(v.wB));
  const Eigen::Vector3d xp = joint.schurInverse * (rp - joint.blockTimesCoupling.transpose() * rn);
  const Eigen::Vector4d xn =
      m_blockInverses[static_cast<std::size_t>(pair.block)] * rn - joint.blockTimesCoupling * xp;
  if (!xp.allFinite() || !xn.allFinite()) return false;

  // The block fixes what the friction does to the bodies: its total along
  // t1 and t2 and its moment about n through c (the patterns add x_p to
  // each). For points in the contact plane nothing else about it moves the
  // bodies, so it is shared anew in proportion to the new normal impulses,
  // force through their centre c', moment about n as lambda_i (n x (p_i -
  // c')) (the share that lets the pair stick longest). Accepted only if the
  // normals push and every point's friction then stays inside its bound
  // (the pair sticks). With mu > 0 a pulling normal also fails the bound
  // (it is negative); the normal test says why first.
  std::array<double, 4> normal{};
  std::array<double, 4> share{};  // each point's part of the new load
  double load = 0.0;
  for (int i = 0; i < count; ++i) {
    const std::size_t si = static_cast<std::size_t>(i);
    normal[si] = normals[i].impulse + xn[i];
    if (normal[si] < 0.0) {
      state = kJointRefused;
      ++m_jointCounts.refused;
      return false;
    }
    load += normal[si];
  }
  if (!(load > 0.0)) return false;
  for (int i = 0; i < count; ++i)
    share[static_cast<std::size_t>(i)] = normal[static_cast<std::size_t>(i)] / load;
  double force[2] = {xp[0], xp[1]};
  double moment = joint.spin ? xp[2] : 0.0;
  double centre[2] = {0.0, 0.0};
  for (int i = 0; i < count; ++i) {
    const double f1 = rows[2 * i].impulse;
    const double f2 = rows[2 * i + 1].impulse;
    force[0] += f1;
    force[1] += f2;
    moment += joint.plane(i, 0) * f2 - joint.plane(i, 1) * f1;  // (rho x f) . n, t1 x t2 = n
    const double u = share[static_cast<std::size_t>(i)];
    centre[0] += u * joint.plane(i, 0);
    centre[1] += u * joint.plane(i, 1);
  }
  double spread = 0.0;
  for (int i = 0; i < count; ++i) {
    const double u = share[static_cast<std::size_t>(i)];
    const double d0 = joint.plane(i, 0) - centre[0];
    const double d1 = joint.plane(i, 1) - centre[1];
    spread += u * (d0 * d0 + d1 * d1);
  }
  // The moment about n through c' that the shared torque must carry.
  double twist = 0.0;
  if (joint.spin) {
    if (!(spread > kLeastLever * kLeastLever)) {
      state = kJointRefused;  // the load sits at one place: it cannot carry a torque
      ++m_jointCounts.refused;
      return false;
    }
    twist = (moment - (centre[0] * force[1] - centre[1] * force[0])) / spread;
  }
  std::array<double, 8> friction{};
  for (int i = 0; i < count; ++i) {
    const std::size_t si = static_cast<std::size_t>(i);
    const double u = share[si];
    // n x (rho - c') in the tangent basis is (-(rho2 - c2), rho1 - c1).
    const double part[2] = {u * (force[0] - twist * (joint.plane(i, 1) - centre[1])),
                            u * (force[1] + twist * (joint.plane(i, 0) - centre[0]))};
    const double bound = pair.friction * normal[si];
    for (int k = 0; k < 2; ++k) {
      if (std::abs(part[k]) > bound) {
        state = kJointRefused;
        ++m_jointCounts.refused;
        return false;
      }
      friction[static_cast<std::size_t>(2 * i + k)] = part[k];
    }
  }
  // Applied row by row, so the velocities are exactly what the stored
  // impulses say (next step's warm start starts from them).
  ChangeTracker tracker(pair);
  for (int i = 0; i < count; ++i) {
    const double delta = normal[static_cast<std::size_t>(i)] - normals[i].impulse;
    normals[i].impulse = normal[static_cast<std::size_t>(i)];
    if constexpr (kTrack) tracker.Note(delta, normals[i].mass);
    v.Apply(delta, n, normals[i].j, pair.invMassA, pair.invMassB);
  }
  for (int row = 0; row < 2 * count; ++row) {
    FrictionRow& f = rows[row];
    const double delta = friction[static_cast<std::size_t>(row)] - f.impulse;
    f.impulse = friction[static_cast<std::size_t>(row)];
    if constexpr (kTrack) tracker.Note(delta, f.mass);
    v.Apply(delta, pair.tangent[row % 2], f.j, pair.invMassA, pair.invMassB);
  }
  v.Store(a, b);
  if constexpr (kTrack) m_largestChange = std::max(m_largestChange, tracker.largest);
  state = kJointAccepted;
  ++m_jointCounts.accepted;
  return true;
}

template bool ContactSolver::SolveJointBlock<true>(const PairRows& pair);
template bool ContactSolver::SolveJointBlock<false>(const PairRows& pair);

}  // namespace talus
