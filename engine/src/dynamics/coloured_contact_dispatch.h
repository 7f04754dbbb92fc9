// ColouredContactDispatch: ContactOrder::ByColour's passes over a
// ContactRowSet, spread over threads. It packs the rows into a
// WideContactSolver (coloured, four pairs to a bundle; dynamics/
// wide_contact_solver.h) and runs each pass as a chain of phases through a
// PhaseRunner (jobs/job_pool.h): each colour's bundles split into chunks,
// then the overflow pairs as one chunk with the scalar sweeps
// (dynamics/sequential_impulse_sweeps.h), each phase finished before the
// next starts. A colour's bundles touch disjoint rows and movable bodies,
// so results do not depend on how a phase is cut or who runs it (tested).
#pragma once

#include <vector>

#include "dynamics/contact_row_set.h"
#include "dynamics/coupled_block_solver.h"
#include "dynamics/sequential_impulse_sweeps.h"
#include "dynamics/wide_contact_solver.h"
#include "jobs/job_pool.h"
#include "talus/step_statistics.h"

namespace talus {

class ColouredContactDispatch {
 public:
  /// Colours and packs the rows; adds the colours and overflow pairs to `stats`.
  void Build(const ContactRowSet& rows, const PhaseRunner& runner, StepStatistics& stats);
  /// Applies the loaded impulses: each colour's bundles, then the overflow pairs.
  void WarmStart(ContactRowSet& rows, const PhaseRunner& runner);
  /// `sweeps` coloured sweeps as one chain of phases (each sweep: each
  /// colour's normal rows, the overflow pairs' through `overflow`; then the
  /// friction rows likewise). With `track`, returns the largest tracked
  /// change (max is exact in any order, so the cut does not matter).
  double Sweeps(ContactRowSet& rows, CoupledBlockSolver& coupled, SequentialImpulseSweeps& overflow,
                int sweeps, bool track, const PhaseRunner& runner);
  /// Writes the bundles' impulses back into the scalar rows.
  void Unpack(ContactRowSet& rows, const PhaseRunner& runner) const;
  /// The packed rows of the last Build.
  [[nodiscard]] const WideContactSolver& Wide() const { return m_wide; }

 private:
  WideContactSolver m_wide;
  std::vector<JobPhase> m_phases;  ///< scratch: the chain of the coloured passes
};

}  // namespace talus
