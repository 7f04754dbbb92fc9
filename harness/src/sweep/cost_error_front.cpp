// One run's (cost, error) point, Pareto fronts, the comparison at one
// budget and at equal cost (cost_error_front.h).
#include "talus/harness/sweep/cost_error_front.h"
#include "support/numbers.h"

#include <algorithm>
#include <cmath>

namespace talus::harness {
namespace {}  // namespace

double BestError(const CostErrorPoint& point) {
  const double value = std::isnan(point.best) ? point.error : point.best;
  return std::isnan(value) ? kInfinity : value;
}

double WorstError(const CostErrorPoint& point) {
  const double value = std::isnan(point.worst) ? point.error : point.worst;
  return std::isnan(value) ? kInfinity : value;
}

double RunErrorScalar(const RunResult& result) {
  if (!result.error.empty()) return std::numeric_limits<double>::quiet_NaN();
  double worst = std::numeric_limits<double>::quiet_NaN();
  for (const MetricResult& metric : result.metrics) {
    // Every metric with a tolerance counts, gated or not (an ungated truth
    // is a known shortfall, still a truth to be accurate against).
    if (!(metric.tolerance.absolute > 0.0 || metric.tolerance.relative > 0.0)) continue;
    const double scale = metric.tolerance.absolute + metric.tolerance.relative * std::abs(metric.truth);
    // Against the continuous truth, not the integrator-exact one
    // (MetricResult::error): a finer step must be able to earn a smaller
    // error, and an engine exact in continuous time must not be charged
    // for leaving symplectic Euler's sequence. The agreement with the
    // integrator-exact answer stays in each metric's error.
    const double error = metric.measured - metric.truth;
    double value = kInfinity;
    if (std::isfinite(error) && scale > 0.0) value = std::abs(error) / scale;
    worst = std::isnan(worst) ? value : std::max(worst, value);
  }
  return worst;
}

double RunCost(const RunResult& result) { return result.wallSeconds; }

// Sort by (cost, worst, index), then keep each point whose worst error is
// below every cheaper point's: the classic staircase sweep, O(n log n).
std::vector<int> ParetoFront(const std::vector<CostErrorPoint>& points) {
  std::vector<int> order(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    if (points[a].cost != points[b].cost) return points[a].cost < points[b].cost;
    return WorstError(points[a]) < WorstError(points[b]);
  });
  std::vector<int> front;
  double best = kInfinity;
  for (int i : order) {
    if (WorstError(points[i]) < best) {
      front.push_back(i);
      best = WorstError(points[i]);
    }
  }
  return front;
}

double AffordableCost(const CostErrorPoint& point) {
  return std::isnan(point.cheapestRun) ? point.cost : std::min(point.cost, point.cheapestRun);
}

const CostErrorPoint* FrontPointAt(const std::vector<CostErrorPoint>& points, double budget) {
  const CostErrorPoint* chosen = nullptr;
  for (const CostErrorPoint& point : points) {
    if (!(AffordableCost(point) <= budget)) continue;
    const bool better = chosen == nullptr || WorstError(point) < WorstError(*chosen) ||
                        (WorstError(point) == WorstError(*chosen) && BestError(point) < BestError(*chosen));
    if (better) chosen = &point;
  }
  return chosen;
}

double FrontErrorAt(const std::vector<CostErrorPoint>& points, double budget) {
  const CostErrorPoint* point = FrontPointAt(points, budget);
  return point != nullptr ? WorstError(*point) : kInfinity;
}

BudgetOutcome CompareAtBudget(const CostErrorPoint* first, const CostErrorPoint* second) {
  const double firstBest = first != nullptr ? BestError(*first) : kInfinity;
  const double firstWorst = first != nullptr ? WorstError(*first) : kInfinity;
  const double secondBest = second != nullptr ? BestError(*second) : kInfinity;
  const double secondWorst = second != nullptr ? WorstError(*second) : kInfinity;
  // A failure in any draw is no round-off difference: it counts against
  // the side that had it, however good its other copies were.
  const bool firstFailed = firstWorst == kInfinity;
  const bool secondFailed = secondWorst == kInfinity;
  if (firstFailed || secondFailed) {
    if (firstFailed == secondFailed) return BudgetOutcome::kTie;
    return firstFailed ? BudgetOutcome::kSecond : BudgetOutcome::kFirst;
  }
  // Worst against the other's best: instability widens a side's own range
  // and so can only cost it wins, never buy it one.
  if (firstWorst < secondBest) return BudgetOutcome::kFirst;
  if (secondWorst < firstBest) return BudgetOutcome::kSecond;
  return BudgetOutcome::kTie;
}

std::vector<double> ComparedBudgets(const std::vector<std::vector<CostErrorPoint>>& fronts,
                                    double& matchedCost) {
  matchedCost = 0.0;
  if (fronts.empty()) return {};
  double matched = -kInfinity;
  for (const auto& front : fronts) {
    if (front.empty()) return {};
    double cheapest = kInfinity;
    for (const CostErrorPoint& point : front) cheapest = std::min(cheapest, point.cost);
    matched = std::max(matched, cheapest);
  }
  matchedCost = matched;
  std::vector<double> budgets;
  for (const auto& front : fronts) {
    for (const CostErrorPoint& point : front) {
      if (point.cost >= matched) budgets.push_back(point.cost);
    }
  }
  std::sort(budgets.begin(), budgets.end());
  budgets.erase(std::unique(budgets.begin(), budgets.end()), budgets.end());
  return budgets;
}

FrontComparison CompareFronts(const std::vector<std::vector<CostErrorPoint>>& fronts) {
  FrontComparison comparison;
  comparison.wins.assign(fronts.size(), 0);
  comparison.errorAtMatched.assign(fronts.size(), kInfinity);
  comparison.spreadAtMatched.assign(fronts.size(), 0.0);
  const std::vector<double> budgets = ComparedBudgets(fronts, comparison.matchedCost);
  if (budgets.empty()) return comparison;
  const double matched = comparison.matchedCost;
  comparison.budgets = static_cast<int>(budgets.size());
  for (std::size_t f = 0; f < fronts.size(); ++f) {
    const CostErrorPoint* point = FrontPointAt(fronts[f], matched);
    comparison.errorAtMatched[f] = point != nullptr ? point->error : kInfinity;
    comparison.spreadAtMatched[f] = point != nullptr ? point->spread : 0.0;
  }
  std::vector<const CostErrorPoint*> at(fronts.size());
  for (double budget : budgets) {
    for (std::size_t f = 0; f < fronts.size(); ++f) at[f] = FrontPointAt(fronts[f], budget);
    // A backend wins the budget only when it is better than every other.
    for (std::size_t f = 0; f < fronts.size(); ++f) {
      bool beatsAll = true;
      for (std::size_t g = 0; g < fronts.size() && beatsAll; ++g) {
        if (g != f) beatsAll = CompareAtBudget(at[f], at[g]) == BudgetOutcome::kFirst;
      }
      if (beatsAll && fronts.size() > 1) ++comparison.wins[f];
    }
  }
  int mostWins = 0;
  for (std::size_t f = 0; f < fronts.size(); ++f) {
    if (comparison.wins[f] > mostWins) {
      mostWins = comparison.wins[f];
      comparison.winner = static_cast<int>(f);
    } else if (comparison.wins[f] == mostWins && mostWins > 0) {
      comparison.winner = -1;
    }
  }
  return comparison;
}
}  // namespace talus::harness
