// The analysis of a stepping sweep (the same runs at several time steps
// and solver iterations, runner.h ExpandStepping): the results grouped per
// scenario instance into curves (one per backend and iterations), each
// backend's Pareto front marked, the most accurate backend at equal cost
// named (CompareFronts) and every engine family judged against every other
// (CompareFamilies), then the family verdicts tallied over the instances.
// Everything is a pure function of the results, in their order, so equal
// results give equal text.
#pragma once

#include <string>
#include <vector>

#include "talus/harness/run/results_file.h"
#include "talus/harness/sweep/cost_error_front.h"
#include "talus/harness/sweep/family_verdict.h"

namespace talus::harness {

/// One curve: a backend at one iteration count across the time steps.
struct SweepCurve {
  std::string backend;
  int iterations = 0;                  ///< as asked (0 = engine default)
  std::vector<double> timeSteps;       ///< seconds, as run
  std::vector<CostErrorPoint> points;  ///< same order as timeSteps
  std::vector<bool> onFront;           ///< on its backend's Pareto front
  std::string family;                  ///< its engine family (EngineFamily)
};

/// One scenario instance (its run id without the stepping values).
struct SweepGroup {
  std::string id;                     ///< e.g. "box_slide[mu=0.3,v0=1]"
  std::vector<SweepCurve> curves;     ///< backend-major in the results' backend order, then iterations
  std::vector<std::string> backends;  ///< compared, in the results' order
  FrontComparison comparison;         ///< over `backends`
  FamilyVerdict families;             ///< every engine family against every other
};

/// The backends a sweep analysis treats as having no iteration setting:
/// ODE's dWorldStep solves its LCP directly, so iterations do not apply.
inline const std::vector<std::string> kSweepSingleSetting{"ode-step", "ode-step-tuned"};

/// Groups the results of every instance with a truth into curves (a failed
/// run of such an instance is a point of infinite error at its cost; an
/// instance no run measured a truth in is left out); backends in
/// `singleSetting` ignore iterations (e.g. "ode-step"): only their first
/// iteration count is kept.
std::vector<SweepGroup> AnalyseSweep(const ResultsFile& file, const std::vector<std::string>& singleSetting);

/// Per pair of families, over the instances where both ran: how many the
/// first was better in, tied, and the second was better in.
struct FamilyTally {
  std::string first, second;
  int firstBetter = 0, ties = 0, secondBetter = 0;
  int splits = 0;  ///< of the ties, those where each won some budget
};
/// In the order pairs first appear (Talus's first).
std::vector<FamilyTally> TallyFamilies(const std::vector<SweepGroup>& groups);

}  // namespace talus::harness
