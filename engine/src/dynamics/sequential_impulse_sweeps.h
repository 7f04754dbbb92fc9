// SequentialImpulseSweeps: projected Gauss-Seidel over the rows of a
// ContactRowSet, row by row or a pair's normal rows as one block, and the
// warm start that applies the loaded impulses (Sequential Impulses, section
// 3 of the write-up after Catto, GDC 2005-2009).
//
// Normal rows. Impulse dlambda = -m_n (n . dv - target) (the row's terms
//   in dynamics/contact_row_set.h); accumulated lambda clamped to [0, inf)
//   (contacts push, never pull), the body velocities changed by the
//   clamped difference along +n for A and -n for B.
//
// Block solve (option, default on). A pair's 2-4 normal rows are solved
//   together: dlambda = K+ (target - J v), K = J M^-1 J^T (its
//   pseudo-inverse from ContactRowSet), accepted when every accumulated
//   impulse stays >= 0, else row by row. Box2D v2.4's two-point block
//   solver extended to four points. With FrictionSolve::CoupledBlock (and
//   Adaptive's loaded groups) a face pair's normals and friction are tried
//   as one block first (dynamics/coupled_block_solver.h).
//
// Friction. Accumulated impulse clamped to [-mu lambda_n, mu lambda_n]
//   with the point's current lambda_n, re-read every time after the normal
//   row moved.
//
// Order. Each sweep visits all normal rows, then all friction rows.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "dynamics/contact_row_set.h"
#include "dynamics/contact_rows.h"
#include "dynamics/coupled_block_solver.h"
#include "dynamics/manifold_friction.h"

namespace talus {

class SequentialImpulseSweeps {
 public:
  /// Applies the loaded impulses of every pair to the gathered velocities.
  static void WarmStart(ContactRowSet& rows);
  /// The loaded impulses of one pair: lambda_n n + lambda_1 t1 + lambda_2
  /// t2 per point, through the rows' precomputed images.
  static void WarmStartPair(ContactRowSet& rows, const PairRows& pair);
  /// One sweep over every pair: normals, then friction. With `track`,
  /// returns the largest velocity change of a row of a new pair (m/s),
  /// else 0.
  double Sweep(ContactRowSet& rows, CoupledBlockSolver& coupled, bool track);
  /// The normal rows (or, with `friction`, the friction rows) of the pairs
  /// `pairs` (indices into the rows' pairs), one by one in order; returns
  /// as Sweep does.
  double SolvePairs(ContactRowSet& rows, CoupledBlockSolver& coupled, std::span<const int> pairs,
                    bool friction, bool track);

 private:
  template <bool kTrack>
  void SweepAll(ContactRowSet& rows, CoupledBlockSolver& coupled);
  template <bool kTrack>
  void SolvePairList(ContactRowSet& rows, CoupledBlockSolver& coupled, std::span<const int> pairs,
                     bool friction);
  template <bool kTrack>
  void SolveNormals(ContactRowSet& rows, CoupledBlockSolver& coupled, const PairRows& pair);
  template <bool kTrack>
  void SolvePairNormals(ContactRowSet& rows, CoupledBlockSolver& coupled, const PairRows& pair);
  template <bool kTrack>
  bool SolveNormalBlock(ContactRowSet& rows, const PairRows& pair);
  template <bool kTrack>
  void SolveFriction(ContactRowSet& rows, const CoupledBlockSolver& coupled, const PairRows& pair);

  /// The index of `pair` in the rows' pairs.
  static std::size_t PairIndex(const ContactRowSet& rows, const PairRows& pair) {
    return static_cast<std::size_t>(&pair - rows.Pairs().data());
  }

  double m_largestChange = 0.0;  ///< m/s, the largest row velocity change of this sweep
  /// Per pair, the loads of its manifold friction rows, written by its
  /// normal pass and read by its friction pass of the same sweep (entries
  /// of other pairs are left as they are).
  std::vector<ManifoldLoad> m_loads;
};

}  // namespace talus
