// SolverBodies: the dense array of velocities the contact solver's sweeps
// read and write, one small entry per body that takes part in a contact
// this step (Bullet's btSolverBody, Box2D v3's b2BodyState).
//
// Why. A BodySim is 640 bytes, ten cache lines (pose, forces,
// three inertia matrices); a sweep touches only the two velocities. Each
// row update used to load and store them through the BodySim; gathered
// into 48-byte entries the ~1,240 bodies of the pyramid fit in L2 and a
// row touches one line per body.
//
// Layout. `Velocity(i)` (v, w) in one vector, the split-impulse pseudo
// velocities in a second one of the same length (only that option reads
// them), the cold per-entry facts (body index, inverse mass and world
// inverse inertia as the solver sees them, whether contacts move it) in
// others. Entries are numbered in the order Add first sees their bodies,
// so the numbering is a function of the contact order alone (determinism).
//
// Invariants: an entry's inverse mass and inverse inertia are zero when
// contacts cannot move its body (static, kinematic, asleep): the rows
// precompute their terms from them, so a sweep applies exactly zero to such
// a body without a branch, and Scatter never writes it back, so its
// velocities stay bit-identical. Kinematic bodies keep their own entry with
// their real velocities, which the rows read.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "dynamics/body_sim.h"
#include "talus/math.h"

namespace talus {

/// Linear (m/s) and angular (rad/s, world axes) velocity of one solver body.
struct SolverVelocity {
  Vec3 v = Vec3::Zero();
  Vec3 w = Vec3::Zero();
};
// The entry every row loads and stores: 48 bytes, so a row touches one
// cache line per body (at most two when an entry straddles a line), and
// the pyramid's ~1,240 bodies' entries fit in L2 (see above).
static_assert(sizeof(SolverVelocity) == 48,
              "SolverVelocity: 48 bytes, one cache line per body a row touches");

class SolverBodies {
 public:
  /// Forgets every entry; `bodyCount` is the size of the body array the
  /// next Adds index. Keeps the capacity (nothing allocates in steady state).
  void Reset(std::size_t bodyCount) {
    // Only the slots used last step need clearing: O(entries), not O(bodies).
    for (const int body : m_bodyIndex) m_entryOfBody[static_cast<std::size_t>(body)] = -1;
    m_entryOfBody.resize(bodyCount, -1);
    m_velocities.clear();
    m_pseudo.clear();
    m_bodyIndex.clear();
    m_invMass.clear();
    m_invInertia.clear();
  }

  /// The entry of body `bodyIndex`, gathering its velocities on first use.
  /// Returns the entry's index.
  int Add(std::span<const BodySim> bodies, int bodyIndex) {
    int& entry = m_entryOfBody[static_cast<std::size_t>(bodyIndex)];
    if (entry >= 0) return entry;
    const BodySim& body = bodies[static_cast<std::size_t>(bodyIndex)];
    const bool moves = body.IsSolverDynamic();
    entry = Count();
    m_velocities.push_back({body.linearVelocity, body.angularVelocity});
    m_pseudo.push_back({});
    m_bodyIndex.push_back(bodyIndex);
    m_invMass.push_back(moves ? body.invMass : 0.0);
    m_invInertia.push_back(moves ? body.invInertiaWorld : Mat3::Zero());
    return entry;
  }

  /// Writes the velocities of the entries contacts can move back to their
  /// bodies, and with `pseudo` the split-impulse pseudo velocities too.
  void Scatter(std::span<BodySim> bodies, bool pseudo) const {
    for (std::size_t i = 0; i < m_velocities.size(); ++i) {
      if (m_invMass[i] == 0.0) continue;
      BodySim& body = bodies[static_cast<std::size_t>(m_bodyIndex[i])];
      body.linearVelocity = m_velocities[i].v;
      body.angularVelocity = m_velocities[i].w;
      if (pseudo) {
        body.pseudoLinear = m_pseudo[i].v;
        body.pseudoAngular = m_pseudo[i].w;
      }
    }
  }

  [[nodiscard]] int Count() const { return static_cast<int>(m_velocities.size()); }
  SolverVelocity& Velocity(int i) { return m_velocities[static_cast<std::size_t>(i)]; }
  [[nodiscard]] const SolverVelocity& Velocity(int i) const {
    return m_velocities[static_cast<std::size_t>(i)];
  }
  SolverVelocity& Pseudo(int i) { return m_pseudo[static_cast<std::size_t>(i)]; }
  [[nodiscard]] int BodyIndex(int i) const { return m_bodyIndex[static_cast<std::size_t>(i)]; }
  /// 1/kg; 0 for a body contacts cannot move.
  [[nodiscard]] double InvMass(int i) const { return m_invMass[static_cast<std::size_t>(i)]; }
  /// 1/(kg m^2), world axes at Add; zero for a body contacts cannot move.
  [[nodiscard]] const Mat3& InvInertia(int i) const { return m_invInertia[static_cast<std::size_t>(i)]; }
  [[nodiscard]] bool Moves(int i) const { return m_invMass[static_cast<std::size_t>(i)] > 0.0; }

 private:
  std::vector<int> m_entryOfBody;  ///< by body index; -1 when the body has no entry
  std::vector<SolverVelocity> m_velocities;
  std::vector<SolverVelocity> m_pseudo;
  std::vector<int> m_bodyIndex;
  std::vector<double> m_invMass;
  std::vector<Mat3> m_invInertia;
};

}  // namespace talus
