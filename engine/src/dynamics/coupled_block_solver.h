// CoupledBlockSolver: FrictionSolve::CoupledBlock, a face contact's normal rows
// and its friction solved as one block (coupled_block_solver.cpp says why),
// with its per-block state of the step and its counts.
//
// Derivation (face contacts of 3-4 points with a normal block). With
//   weights w_i = lambda_n,i / sum lambda_n, three friction impulse
//   patterns over the pair's points: P1_i = w_i t1, P2_i = w_i t2 (a force
//   through the centre of pressure c) and P3_i = lambda_n,i (n x (p_i - c))
//   / S, S = sum lambda_n,i |n x (p_i - c)|^2 (a unit torque about n
//   through c, no net force). Each is a generalised row
//   J_p = [F_p, sum rA_i x P_p,i, -F_p, -sum rB_i x P_p,i]. The pair's
//   normal rows and the three patterns are solved as one system K x = r
//   (targets for the normals, zero slip and spin for the patterns),
//   through the Schur complement of the normal block's pseudo-inverse. The
//   friction's new total force and moment about n are then shared among
//   the points in proportion to the new normal impulses (for points in the
//   contact plane that moves nothing), and the block is accepted when every
//   normal impulse stays >= 0 and every point's friction inside
//   [-mu lambda_n, mu lambda_n] per tangent; the pair's friction rows are
//   then skipped in that sweep. Otherwise (sliding, lifting) the normal
//   block and the per-point friction rows run as usual, and the block is
//   not tried again that step.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "dynamics/contact_row_set.h"
#include "dynamics/contact_rows.h"

namespace talus {

struct PairVelocities;

class CoupledBlockSolver {
 public:
  /// Tries of the block in the last step's sweeps.
  struct Counts {
    std::int64_t accepted = 0;  ///< the pair stuck: normals and friction solved as one block
    std::int64_t refused = 0;   ///< a pulling normal, a friction past its bound, or no lever for the twist
  };

  /// Forgets the last step: `enabled` (FrictionSolve::CoupledBlock or Adaptive selected)
  /// for the `blocks` normal blocks of this step's rows.
  void Reset(bool enabled, int blocks);
  /// Whether the block applies to `pair`: selected, a normal block,
  /// friction not on the manifold's rows (Adaptive gives those to lightly
  /// loaded faces), and at least three points (a face). Edge contacts (two
  /// points) keep the per-point rows: measured, the block on them changed
  /// how boxes tip over an edge (box_toss at 1/120 s, 5 sweeps, settled on
  /// another face, 36 cm from its converged run; tall_box_tipping's tip
  /// further from its truth), for no accuracy gained anywhere in the sweep
  /// (docs/dynamics.md).
  [[nodiscard]] bool Applies(const PairRows& pair) const {
    return m_enabled && pair.block >= 0 && pair.hasFriction && !pair.manifoldFriction && pair.pointCount >= 3;
  }
  /// The block on `pair` (Applies): true when accepted (normals and
  /// friction written and applied). Builds the operator at the step's
  /// first try. With kTrack, raises `largest` to the rows' largest
  /// velocity change (ChangeTracker).
  template <bool kTrack>
  bool Solve(ContactRowSet& rows, const PairRows& pair, double& largest);
  /// Whether the block solved `pair`'s friction in this sweep's normal pass
  /// (its friction rows are then skipped).
  [[nodiscard]] bool SolvedFriction(const PairRows& pair) const {
    return Applies(pair) && m_state[static_cast<std::size_t>(pair.block)] == kAccepted;
  }
  [[nodiscard]] const Counts& LastCounts() const { return m_counts; }

 private:
  /// Per block, the last outcome this step. Unbuilt: not tried yet this
  /// step (the operator is built at the first try; an operator that is not
  /// usable counts as refused). Refused (the pair slides or lifts): later
  /// sweeps of the step do not try again, a sliding pair stays sliding
  /// within a step. Accepted in this sweep's normal pass: the pair's
  /// friction rows are skipped in its friction pass, because the three
  /// patterns span every friction impulse that moves the bodies when the
  /// points are coplanar (a net force in the plane and a torque about n),
  /// so the rows could only redistribute impulse among the points.
  enum State : unsigned char { kUnbuilt, kUntried, kRefused, kAccepted };
  /// How one try ended, before the state records it.
  enum class Outcome { kAccepted, kRefused, kNotSolved };
  /// The friction the accepted block gives each point, per tangent.
  using PointFriction = std::array<double, 8>;

  /// The patterns and solve operator of `pair` from its rows and
  /// warm-started impulses (built at the pair's first try of the step,
  /// before they change).
  [[nodiscard]] static CoupledBlockRows Build(const ContactRowSet& rows, const PairRows& pair);
  /// One try of the block with the operator `coupled`; records the outcome in `state`.
  template <bool kTrack>
  bool Try(ContactRowSet& rows, const PairRows& pair, const CoupledBlockRows& coupled, State& state,
           double& largest);
  /// The block's solve: the new normal impulses in `normal`, the
  /// friction's share per point in `friction`, or why not.
  static Outcome SolveBlock(const ContactRowSet& rows, const PairRows& pair, const CoupledBlockRows& coupled,
                            const PairVelocities& v, std::array<double, 4>& normal, PointFriction& friction);

  std::vector<CoupledBlockRows>
      m_blocks;                ///< per block: the operator, stored at the first try unless refused
  std::vector<State> m_state;  ///< per block
  Counts m_counts;
  bool m_enabled = false;
};

}  // namespace talus
