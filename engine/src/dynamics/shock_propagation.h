// ShockPropagation (MethodSettings::shockPropagation): after the velocity
// sweeps, the pairs level by level from the immovable bodies up, each
// pair's lower body held (derivation, levels and which pairs are visited in
// shock_propagation.cpp; measurements in docs/dynamics.md, "Shock
// propagation"). Owns its scratch, kept between steps (no allocation in
// steady state).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "dynamics/body_sim.h"
#include "dynamics/contact.h"
#include "dynamics/contact_row_set.h"
#include "dynamics/contact_rows.h"

namespace talus {

struct PairVelocities;

class ShockPropagation {
 public:
  /// Reads what the pass needs of this step from the rows just built: which
  /// pairs touch (some point within `slop` of contact) and, per solver
  /// body, the velocity it had at the step's start and the one gravity and
  /// the applied forces gave it.
  void Prepare(std::span<const BodySim> bodies, std::span<const Contact> contacts, const ContactRowSet& rows,
               double slop);
  /// Records each solver body's velocity after the warm start (before the
  /// sweeps), which KeepLoadedPairs compares with its start.
  void NoteWarmed(const SolverBodies& bodies);
  /// The pass: up to `maxSweeps` sweeps per level until a sweep changes no
  /// velocity by more than `tolerance` (m/s). Returns the sweeps run.
  int Propagate(ContactRowSet& rows, int maxSweeps, double tolerance);

 private:
  /// Which bodies of a pair the pass moves: their inverse masses, zero for
  /// the held one.
  struct Sides {
    bool moveA = true;
    bool moveB = true;
    double invMassA = 0.0;
    double invMassB = 0.0;
  };

  /// The levels of this step's solver bodies and the pair order.
  void AssignLevels(const ContactRowSet& rows);
  /// The adjacency of the solver bodies through the touching pairs (CSR).
  void BuildAdjacency(const ContactRowSet& rows);
  /// Breadth first from every immovable body: each body's level.
  void LevelBodies(const ContactRowSet& rows);
  void KeepLoadedPairs(const ContactRowSet& rows);
  /// Whether the pass keeps the pair at m_order[o] (KeepLoadedPairs).
  bool KeepPair(const PairRows& pair);
  [[nodiscard]] int PairLevel(const PairRows& pair) const;
  [[nodiscard]] Sides SidesOf(const PairRows& pair) const;
  double Sweep(ContactRowSet& rows, std::size_t begin, std::size_t end);
  bool HeldBlock(ContactRowSet& rows, std::size_t order, const PairRows& pair, const Sides& sides,
                 PairVelocities& v, double& largest);
  static void HeldNormals(ContactRowSet& rows, const PairRows& pair, const Sides& sides, PairVelocities& v,
                          double& largest);
  static void HeldFriction(ContactRowSet& rows, const PairRows& pair, const Sides& sides, PairVelocities& v,
                           double& largest);

  std::vector<unsigned char> m_touching;  ///< per pair: some point within one slop of touching
  std::vector<int> m_levels;              ///< per solver body
  std::vector<int> m_adjStart;            ///< CSR offsets of the bodies' neighbours
  std::vector<int> m_adj;
  std::vector<int> m_fill;
  std::vector<int> m_queue;
  std::vector<int> m_order;    ///< pair indices with a level, by level
  std::vector<Vec3> m_push;    ///< per solver body: the velocity gravity and forces gave it this step, m/s
  std::vector<Vec3> m_start;   ///< per solver body: its velocity at the step's start, m/s
  std::vector<Vec3> m_warmed;  ///< per solver body: its velocity after the warm start, m/s
  std::vector<unsigned char> m_loaded;  ///< per solver body: carries a load heavier than a support
  std::vector<unsigned char> m_keep;
  /// Per kept pair with a normal block: the block's pseudo-inverse with the
  /// held body's terms left out (built at the pass's first sweep of it).
  std::vector<Eigen::Matrix4d> m_blocks;
  std::vector<unsigned char> m_blockBuilt;  ///< per entry of m_order: the pass visits it
};

}  // namespace talus
