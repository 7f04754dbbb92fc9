// Every engine family against every other in one scenario instance
// (family_verdict.h).
#include "talus/harness/sweep/family_verdict.h"
#include "support/numbers.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace talus::harness {
namespace {}  // namespace

std::string EngineFamily(const RunResult& result) {
  for (const Setting& setting : result.settings) {
    if (setting.key != "engine") continue;
    const std::size_t start = setting.value.find_first_not_of(' ');
    if (start == std::string::npos) break;
    const std::size_t end = setting.value.find(' ', start);
    return setting.value.substr(start, end == std::string::npos ? std::string::npos : end - start);
  }
  return result.backend;
}

std::string_view PairOutcomeName(PairOutcome outcome) {
  switch (outcome) {
    case PairOutcome::kFirstBetter:
      return "better";
    case PairOutcome::kTie:
      return "tie";
    case PairOutcome::kSecondBetter:
      return "worse";
  }
  return "?";
}

namespace {

// The cost `mine` needs to reach `theirs`' most accurate point, over that
// point's cost (family_verdict.h FamilyPair::firstCostRatio).
double CostRatio(const std::vector<CostErrorPoint>& mine, const std::vector<CostErrorPoint>& theirs) {
  const CostErrorPoint* target = FrontPointAt(theirs, kInfinity);
  if (target == nullptr) return std::numeric_limits<double>::quiet_NaN();
  // The cheapest of their most accurate points.
  for (const CostErrorPoint& point : theirs) {
    if (WorstError(point) == WorstError(*target) && point.cost < target->cost) target = &point;
  }
  double needed = kInfinity;
  for (const CostErrorPoint& point : mine) {
    if (WorstError(point) <= WorstError(*target)) needed = std::min(needed, point.cost);
  }
  if (WorstError(*target) == kInfinity || target->cost <= 0.0)
    return std::numeric_limits<double>::quiet_NaN();
  return needed / target->cost;
}

}  // namespace

FamilyPair CompareFamilyPair(const FamilyPoints& first, const FamilyPoints& second) {
  FamilyPair pair;
  pair.first = first.family;
  pair.second = second.family;
  std::vector<double> budgets;
  for (const CostErrorPoint& point : first.points) budgets.push_back(point.cost);
  for (const CostErrorPoint& point : second.points) budgets.push_back(point.cost);
  std::sort(budgets.begin(), budgets.end());
  budgets.erase(std::unique(budgets.begin(), budgets.end()), budgets.end());
  pair.budgets = static_cast<int>(budgets.size());
  double firstWon = kInfinity;
  double secondWon = kInfinity;
  for (double budget : budgets) {
    switch (CompareAtBudget(FrontPointAt(first.points, budget), FrontPointAt(second.points, budget))) {
      case BudgetOutcome::kFirst:
        ++pair.firstWins;
        firstWon = std::min(firstWon, budget);
        break;
      case BudgetOutcome::kSecond:
        ++pair.secondWins;
        secondWon = std::min(secondWon, budget);
        break;
      case BudgetOutcome::kTie:
        break;
    }
  }
  pair.split = pair.firstWins > 0 && pair.secondWins > 0;
  if (pair.firstWins > 0 && pair.secondWins == 0) pair.outcome = PairOutcome::kFirstBetter;
  if (pair.secondWins > 0 && pair.firstWins == 0) pair.outcome = PairOutcome::kSecondBetter;
  pair.budget = pair.outcome == PairOutcome::kFirstBetter    ? firstWon
                : pair.outcome == PairOutcome::kSecondBetter ? secondWon
                                                             : std::min(firstWon, secondWon);
  if (pair.budget == kInfinity) pair.budget = budgets.empty() ? 0.0 : budgets.front();
  const CostErrorPoint* a = FrontPointAt(first.points, pair.budget);
  const CostErrorPoint* b = FrontPointAt(second.points, pair.budget);
  pair.firstBest = a != nullptr ? BestError(*a) : kInfinity;
  pair.firstWorst = a != nullptr ? WorstError(*a) : kInfinity;
  pair.secondBest = b != nullptr ? BestError(*b) : kInfinity;
  pair.secondWorst = b != nullptr ? WorstError(*b) : kInfinity;
  pair.firstCostRatio = CostRatio(first.points, second.points);
  pair.secondCostRatio = CostRatio(second.points, first.points);
  return pair;
}

FamilyVerdict CompareFamilies(std::vector<FamilyPoints> families, std::string_view first) {
  FamilyVerdict verdict;
  // A family without points had no run of this instance with a truth.
  std::erase_if(families, [](const FamilyPoints& family) { return family.points.empty(); });
  std::stable_partition(families.begin(), families.end(),
                        [&](const FamilyPoints& family) { return family.family == first; });
  verdict.families = std::move(families);
  for (std::size_t i = 0; i < verdict.families.size(); ++i) {
    for (std::size_t j = i + 1; j < verdict.families.size(); ++j) {
      verdict.pairs.push_back(CompareFamilyPair(verdict.families[i], verdict.families[j]));
    }
  }
  return verdict;
}
}  // namespace talus::harness
