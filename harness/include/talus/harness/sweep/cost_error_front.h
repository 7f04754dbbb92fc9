// Run time against error, one backend at a time: each result of a
// scenario instance with a truth gives one (cost, error) point (cost the
// run's total wall time, RunResult::wallSeconds, never a median over its
// steps; error the run's error scalar, RunErrorScalar); a run that failed
// is a point too, infinitely bad at its cost. With perturbed copies a
// point also carries its best and worst error over the run and its copies.
// Here: the point, a backend's Pareto front, the comparison of two points
// at one budget and which of several fronts is most accurate at equal
// cost (CompareFronts; definitions in docs/testbed-sweeps.md).
#pragma once

#include <limits>
#include <vector>

#include "talus/harness/run/results_file.h"

namespace talus::harness {

/// The error scalar of one result: the largest |measured - truth| /
/// (absolute + relative |truth|), the distance to the continuous truth (not
/// to MetricResult::truthIntegrator, the integrator-exact answer at the
/// run's step, which the metric's own error keeps), over its metrics that
/// have a tolerance (gated by the
/// CI check or not), so 1 is "exactly at the tolerance". Such a metric
/// that could not be measured (NaN), or whose tolerance scale is 0, makes
/// it +infinity; NaN when the result has no such metric (no truth) or
/// failed to run.
double RunErrorScalar(const RunResult& result);

/// The cost of one result: its total wall seconds (RunResult::wallSeconds:
/// every step's time summed; with perturbed copies the median over the run
/// and its copies); 0 in deterministic mode.
double RunCost(const RunResult& result);

/// One point of a run-time-against-error plot.
struct CostErrorPoint {
  double cost = 0.0;   ///< seconds, RunCost
  double error = 0.0;  ///< the unperturbed run's error scalar, >= 0; +infinity when it failed
  /// max - min of the error over the run and its perturbed copies (shown
  /// beside the error; 0 without copies, +infinity when only some failed).
  double spread = 0.0;
  /// The smallest and largest error over the run and its copies (+infinity
  /// for a failed copy); NaN means "no copies": both are `error`.
  double best = std::numeric_limits<double>::quiet_NaN();
  double worst = std::numeric_limits<double>::quiet_NaN();
  double longestStep = 0.0;  ///< seconds: the run's longest step (NaN when not recorded)
  /// Seconds: the cheapest of the run's and its copies' totals; NaN means
  /// "no copies": `cost`.
  double cheapestRun = std::numeric_limits<double>::quiet_NaN();
};

/// The cost at which a point counts as affordable: the cheapest of its runs
/// (its cost without copies). A budget buys a point when one of its runs
/// was that cheap, so a difference of costs within the points' own timing
/// noise never makes one side "have nothing that cheap".
double AffordableCost(const CostErrorPoint& point);

/// A point's best and worst error (its `error` when it has no copies); a NaN
/// error counts as +infinity (nothing measured).
double BestError(const CostErrorPoint& point);
double WorstError(const CostErrorPoint& point);

/// Indices of the Pareto-optimal points by (cost, worst error): no other
/// point has cost <= and worst <= with one strictly smaller; by increasing
/// cost, of equal points the first kept. Infinite worsts are never on it.
std::vector<int> ParetoFront(const std::vector<CostErrorPoint>& points);

/// The point a budget buys: among the points with AffordableCost <= budget, the one
/// of smallest worst error, then smallest best error, then the first;
/// nullptr when none is that cheap. A failed run's point is chosen only
/// when nothing within the budget did better, so a crash stands at its cost.
const CostErrorPoint* FrontPointAt(const std::vector<CostErrorPoint>& points, double budget);

/// WorstError of FrontPointAt, +infinity when no point is that cheap.
double FrontErrorAt(const std::vector<CostErrorPoint>& points, double budget);

/// Who is more accurate at one budget, each side given by the point its
/// budget buys (nullptr: nothing that cheap, as bad as a failure).
enum class BudgetOutcome { kFirst, kTie, kSecond };
/// A side with an infinite worst error (a failed run or copy, or no point)
/// loses to a side without one; both infinite is a tie. Otherwise a side is
/// better only when its worst copy is below the other side's best copy, so
/// no draw of the round-off lottery could reverse the order; overlapping
/// ranges, equal errors included, are a tie.
BudgetOutcome CompareAtBudget(const CostErrorPoint* first, const CostErrorPoint* second);

/// Which of several fronts (one per backend) is most accurate at equal
/// cost. The compared budgets are the costs of every front point that are
/// >= the matched cost (the largest of the fronts' cheapest costs, the
/// least budget at which every backend has a result); at each budget a
/// backend wins when CompareAtBudget puts it before every other. The
/// winner is the backend with the most wins, -1 when there is no budget or
/// a tie.
struct FrontComparison {
  int winner = -1;                      ///< index into the fronts, -1 for none
  std::vector<int> wins;                ///< per front: budgets won
  int budgets = 0;                      ///< budgets compared
  double matchedCost = 0.0;             ///< seconds: the smallest compared budget
  std::vector<double> errorAtMatched;   ///< per front: FrontErrorAt(matchedCost)
  std::vector<double> spreadAtMatched;  ///< per front: that point's spread (0 when none)
};
FrontComparison CompareFronts(const std::vector<std::vector<CostErrorPoint>>& fronts);

/// The budgets CompareFronts compares: the cost of every front point at or
/// above the matched cost (the largest of the fronts' cheapest costs),
/// increasing, each once. Empty, with `matchedCost` 0, when there is no
/// front or one is empty.
std::vector<double> ComparedBudgets(const std::vector<std::vector<CostErrorPoint>>& fronts,
                                    double& matchedCost);

}  // namespace talus::harness
