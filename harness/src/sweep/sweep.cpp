// Run time against error (sweep.h): the error scalar, Pareto fronts, the
// comparison of fronts at equal cost, the grouping of a stepping sweep's
// results into curves with its JSON and Markdown, and sharding: the "i/n"
// specification, the partition of runs, shard files and their merge.
#include "talus/harness/sweep/sweep.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <type_traits>

#include "support/text_util.h"
#include "talus/harness/scenario/scenario_limits.h"

namespace talus::harness {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

bool IsSteppingValue(const SweepValue& value) { return value.name == "h" || value.name == "iterations"; }

// The run id without the stepping values: what the runs of one scenario
// instance share across the sweep.
std::string InstanceId(const RunResult& result) {
  std::string values;
  for (const SweepValue& value : result.sweepValues) {
    if (IsSteppingValue(value)) continue;
    values.append(values.empty() ? "" : ",").append(value.name).append("=").append(value.value);
  }
  return values.empty() ? result.scenario : Concat({result.scenario, "[", values, "]"});
}

std::string Number(double value) {
  if (std::isnan(value)) return "-";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return FormatNumber(value, 3);
}

// An error with its noise floor when it has one: "0.5 (spread 0.02)", the
// error moved by 0.02 between the point's perturbed copies (max - min).
std::string ErrorText(double error, double spread) {
  return spread > 0.0 ? Concat({Number(error), " (spread ", Number(spread), ")"}) : Number(error);
}

nlohmann::ordered_json JsonNumber(double value) {
  if (!std::isfinite(value)) return nullptr;
  return value;
}

nlohmann::ordered_json FamilyPairJson(const FamilyPair& pair) {
  return {{"first", pair.first},
          {"second", pair.second},
          {"outcome", PairOutcomeName(pair.outcome)},
          {"split", pair.split},
          {"budgets", pair.budgets},
          {"firstWins", pair.firstWins},
          {"secondWins", pair.secondWins},
          {"budget", pair.budget},
          {"firstBest", JsonNumber(pair.firstBest)},
          {"firstWorst", JsonNumber(pair.firstWorst)},
          {"secondBest", JsonNumber(pair.secondBest)},
          {"secondWorst", JsonNumber(pair.secondWorst)},
          {"firstCostRatio", JsonNumber(pair.firstCostRatio)},
          {"secondCostRatio", JsonNumber(pair.secondCostRatio)}};
}

nlohmann::ordered_json FamilyVerdictJson(const FamilyVerdict& verdict) {
  nlohmann::ordered_json out;
  out["members"] = nlohmann::ordered_json::array();
  for (const FamilyPoints& family : verdict.families)
    out["members"].push_back({{"family", family.family}, {"backends", family.backends}});
  out["pairs"] = nlohmann::ordered_json::array();
  for (const FamilyPair& pair : verdict.pairs) out["pairs"].push_back(FamilyPairJson(pair));
  return out;
}

// A point's error range: "0.5" without copies or when they agree, else
// "0.5 [0.4, 0.9]" (the unperturbed run's, then best and worst copy).
std::string RangeText(double best, double worst) {
  return best == worst ? Number(worst) : Concat({"[", Number(best), ", ", Number(worst), "]"});
}

}  // namespace

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
// point's cost (sweep.h FamilyPair::firstCostRatio).
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

std::vector<FamilyTally> TallyFamilies(const std::vector<SweepGroup>& groups) {
  std::vector<FamilyTally> tallies;
  for (const SweepGroup& group : groups) {
    for (const FamilyPair& pair : group.families.pairs) {
      auto tally = std::find_if(tallies.begin(), tallies.end(), [&](const FamilyTally& t) {
        return (t.first == pair.first && t.second == pair.second) ||
               (t.first == pair.second && t.second == pair.first);
      });
      if (tally == tallies.end()) {
        tallies.push_back({pair.first, pair.second});
        tally = tallies.end() - 1;
      }
      // Oriented as the tally was first met (Talus's pairs have Talus first
      // in every group, so theirs never turn round).
      const bool same = tally->first == pair.first;
      if (pair.outcome == PairOutcome::kTie) {
        ++tally->ties;
        if (pair.split) ++tally->splits;
      } else if ((pair.outcome == PairOutcome::kFirstBetter) == same) {
        ++tally->firstBetter;
      } else {
        ++tally->secondBetter;
      }
    }
  }
  return tallies;
}

std::vector<SweepGroup> AnalyseSweep(const ResultsFile& file, const std::vector<std::string>& singleSetting) {
  // The instances with a truth: some run of them measured one. A failed run
  // of such an instance stays in as an infinitely bad point at its cost; a
  // run of an instance without a truth has nothing to be judged on.
  std::map<std::string, bool> hasTruth;
  for (const RunResult& result : file.results) {
    if (!std::isnan(RunErrorScalar(result))) hasTruth[InstanceId(result)] = true;
  }
  std::vector<SweepGroup> groups;
  std::map<std::string, std::size_t> groupIndex;
  for (const RunResult& result : file.results) {
    const std::string id = InstanceId(result);
    if (!hasTruth.contains(id)) continue;
    double error = RunErrorScalar(result);
    if (std::isnan(error)) {
      // A run of the same scenario that measured nothing: failed, or its
      // truths' metrics all missing (a run refused before stepping).
      error = kInfinity;
    }
    auto [found, added] = groupIndex.try_emplace(id, groups.size());
    if (added) {
      groups.emplace_back();
      groups.back().id = id;
    }
    SweepGroup& group = groups[found->second];
    const bool single =
        std::find(singleSetting.begin(), singleSetting.end(), result.backend) != singleSetting.end();
    SweepCurve* curve = nullptr;
    bool backendSeen = false;
    for (SweepCurve& c : group.curves) {
      if (c.backend != result.backend) continue;
      backendSeen = true;
      if (c.iterations == result.iterations) curve = &c;
    }
    if (curve == nullptr) {
      if (single && backendSeen) continue;
      group.curves.push_back({result.backend, result.iterations, {}, {}, {}, EngineFamily(result)});
      curve = &group.curves.back();
    }
    CostErrorPoint point{.cost = RunCost(result),
                         .error = error,
                         .spread = result.perturbed.errorSpread,
                         .longestStep = result.wallSecondsLongestStep};
    if (!result.perturbed.runSeconds.empty()) {
      point.cheapestRun =
          *std::min_element(result.perturbed.runSeconds.begin(), result.perturbed.runSeconds.end());
    }
    if (!result.perturbed.errors.empty()) {
      point.best = kInfinity;
      point.worst = 0.0;
      for (double e : result.perturbed.errors) {
        const double value = std::isnan(e) ? kInfinity : e;
        point.best = std::min(point.best, value);
        point.worst = std::max(point.worst, value);
      }
    } else if (result.perturbed.copies > 0) {
      // A file from before the copies' errors were kept: only the spread is
      // known, so the range is taken as wide as it could have been.
      point.best = std::max(0.0, error - result.perturbed.errorSpread);
      point.worst = error + result.perturbed.errorSpread;
    }
    curve->timeSteps.push_back(result.timeStep);
    curve->points.push_back(point);
  }
  for (SweepGroup& group : groups) {
    // Backend-major in the file's backend order (stable: iterations stay in
    // the order they were met).
    const auto rank = [&](const std::string& backend) {
      return std::find(file.backends.begin(), file.backends.end(), backend) - file.backends.begin();
    };
    std::stable_sort(group.curves.begin(), group.curves.end(), [&](const SweepCurve& a, const SweepCurve& b) {
      return rank(a.backend) < rank(b.backend);
    });
    std::vector<std::vector<CostErrorPoint>> fronts;
    for (const SweepCurve& curve : group.curves) {
      if (group.backends.empty() || group.backends.back() != curve.backend)
        group.backends.push_back(curve.backend);
    }
    for (const std::string& backend : group.backends) {
      std::vector<CostErrorPoint> all;
      std::vector<std::pair<SweepCurve*, std::size_t>> where;
      for (SweepCurve& curve : group.curves) {
        if (curve.backend != backend) continue;
        curve.onFront.assign(curve.points.size(), false);
        for (std::size_t k = 0; k < curve.points.size(); ++k) {
          all.push_back(curve.points[k]);
          where.emplace_back(&curve, k);
        }
      }
      std::vector<CostErrorPoint> front;
      for (int i : ParetoFront(all)) {
        where[i].first->onFront[where[i].second] = true;
        front.push_back(all[i]);
      }
      if (front.empty() && !all.empty()) {
        // Every run failed: its cheapest stands for it, infinitely bad.
        front.push_back(*std::min_element(all.begin(), all.end(),
                                          [](const auto& a, const auto& b) { return a.cost < b.cost; }));
      }
      fronts.push_back(std::move(front));
    }
    group.comparison = CompareFronts(fronts);
    // Families in the order their first backend appears; each holds the
    // union of its variants' points, failed runs included.
    std::vector<FamilyPoints> families;
    for (const SweepCurve& curve : group.curves) {
      auto family = std::find_if(families.begin(), families.end(),
                                 [&](const FamilyPoints& f) { return f.family == curve.family; });
      if (family == families.end()) {
        families.push_back({curve.family, {}, {}});
        family = families.end() - 1;
      }
      if (family->backends.empty() || family->backends.back() != curve.backend)
        family->backends.push_back(curve.backend);
      family->points.insert(family->points.end(), curve.points.begin(), curve.points.end());
    }
    group.families = CompareFamilies(std::move(families));
  }
  return groups;
}

std::string SweepToJson(const std::vector<SweepGroup>& groups) {
  nlohmann::ordered_json out;
  out["format"] = "talus-testbed-sweep";
  out["version"] = 2;
  out["groups"] = nlohmann::ordered_json::array();
  for (const SweepGroup& group : groups) {
    nlohmann::ordered_json g;
    g["id"] = group.id;
    g["backends"] = group.backends;
    const FrontComparison& c = group.comparison;
    g["winner"] = c.winner >= 0 ? nlohmann::ordered_json(group.backends[c.winner]) : nlohmann::ordered_json();
    g["wins"] = c.wins;
    g["budgets"] = c.budgets;
    g["matchedCost"] = c.matchedCost;
    g["errorAtMatched"] = nlohmann::ordered_json::array();
    for (double e : c.errorAtMatched) g["errorAtMatched"].push_back(JsonNumber(e));
    g["spreadAtMatched"] = nlohmann::ordered_json::array();
    for (double e : c.spreadAtMatched) g["spreadAtMatched"].push_back(JsonNumber(e));
    g["families"] = FamilyVerdictJson(group.families);
    g["curves"] = nlohmann::ordered_json::array();
    for (const SweepCurve& curve : group.curves) {
      nlohmann::ordered_json points = nlohmann::ordered_json::array();
      for (std::size_t k = 0; k < curve.points.size(); ++k) {
        const CostErrorPoint& p = curve.points[k];
        points.push_back({{"timeStep", curve.timeSteps[k]},
                          {"cost", p.cost},
                          {"longestStep", JsonNumber(p.longestStep)},
                          {"error", JsonNumber(p.error)},
                          {"spread", JsonNumber(p.spread)},
                          {"best", JsonNumber(BestError(p))},
                          {"worst", JsonNumber(WorstError(p))},
                          {"front", static_cast<bool>(curve.onFront[k])}});
      }
      g["curves"].push_back({{"backend", curve.backend},
                             {"family", curve.family},
                             {"iterations", curve.iterations},
                             {"points", points}});
    }
    out["groups"].push_back(g);
  }
  out["familyVerdict"] = nlohmann::ordered_json::array();
  for (const FamilyTally& t : TallyFamilies(groups)) {
    out["familyVerdict"].push_back({{"first", t.first},
                                    {"second", t.second},
                                    {"firstBetter", t.firstBetter},
                                    {"ties", t.ties},
                                    {"secondBetter", t.secondBetter},
                                    {"splits", t.splits}});
  }
  return out.dump(2) + "\n";
}

std::string SweepMarkdown(const std::vector<SweepGroup>& groups) {
  std::ostringstream out;
  out << "## Run time against error\n\n"
      << "Error: the largest |error| / tolerance over a run's metrics with a tolerance (1 = at the "
         "tolerance, inf = not measured or failed). Cost: total wall seconds of the run (every step "
         "summed; with perturbed copies the median over the run and its copies). Spread: max - min of a "
         "point's error over its run and its perturbed copies (initial positions moved by round-off, each "
         "copy judged against the truth of its own start). Most accurate at equal cost: most budgets won "
         "from the matched cost up (docs/testbed-sweeps.md).\n\n"
      << "| scenario | most accurate at equal cost | matched cost (s) | error at matched cost | wins |\n"
      << "|---|---|---|---|---|\n";
  for (const SweepGroup& group : groups) {
    const FrontComparison& c = group.comparison;
    std::string errors;
    std::string wins;
    for (std::size_t b = 0; b < group.backends.size(); ++b) {
      errors.append(b ? ", " : "")
          .append(group.backends[b])
          .append(" ")
          .append(ErrorText(c.errorAtMatched[b], c.spreadAtMatched[b]));
      wins.append(b ? ", " : "").append(group.backends[b]).append(" ").append(std::to_string(c.wins[b]));
    }
    out << "| " << group.id << " | " << (c.winner >= 0 ? group.backends[c.winner] : std::string("none (tie)"))
        << " | " << Number(c.matchedCost) << " | " << errors << " | " << wins << " of " << c.budgets
        << " |\n";
  }
  out << "\n### Engine families against each other\n\n"
      << "A family is every variant of one engine (talus, talus-split...; bullet, bullet-f32...), its "
         "points the union of its variants'. Two families are compared at the cost of every point of "
         "either, from the cheapest up; at each budget each family takes its point of smallest worst "
         "error within it. A family is better at a budget when its worst copy is below the other's best "
         "copy, or when the other failed in some copy or has nothing that cheap and it did not; "
         "otherwise the budget is a tie. Better in an instance: better at some budget and worse at none; "
         "a tie otherwise (split: each better at some budget). Cost ratio: the cost the first family "
         "needs to reach the second's most accurate point, over that point's cost.\n\n"
      << "| family | against | better | tie (split) | worse |\n|---|---|---|---|---|\n";
  for (const FamilyTally& t : TallyFamilies(groups)) {
    out << "| " << t.first << " | " << t.second << " | " << t.firstBetter << " | " << t.ties << " ("
        << t.splits << ") | " << t.secondBetter << " |\n";
  }
  out << "\n| scenario | first | against | verdict | budgets won (first, second, of) | at budget s: first "
         "error, second error | cost ratio (first for second's error, second for first's) |\n"
      << "|---|---|---|---|---|---|---|\n";
  for (const SweepGroup& group : groups) {
    for (const FamilyPair& pair : group.families.pairs) {
      out << "| " << group.id << " | " << pair.first << " | " << pair.second << " | "
          << PairOutcomeName(pair.outcome) << (pair.split ? " (split)" : "") << " | " << pair.firstWins
          << ", " << pair.secondWins << ", " << pair.budgets << " | " << Number(pair.budget) << ": "
          << RangeText(pair.firstBest, pair.firstWorst) << ", "
          << RangeText(pair.secondBest, pair.secondWorst) << " | " << Number(pair.firstCostRatio) << ", "
          << Number(pair.secondCostRatio) << " |\n";
    }
  }
  out << "\n### Pareto fronts (time step s, iterations: cost s, longest step s, error)\n\n"
      << "| scenario | backend | front |\n|---|---|---|\n";
  for (const SweepGroup& group : groups) {
    for (const std::string& backend : group.backends) {
      std::vector<std::pair<double, std::string>> front;
      for (const SweepCurve& curve : group.curves) {
        if (curve.backend != backend) continue;
        for (std::size_t k = 0; k < curve.points.size(); ++k) {
          if (!curve.onFront[k]) continue;
          const CostErrorPoint& p = curve.points[k];
          front.emplace_back(p.cost, Concat({"h ", Number(curve.timeSteps[k]), ", it ",
                                             std::to_string(curve.iterations), ": ", Number(p.cost), ", ",
                                             Number(p.longestStep), ", ", ErrorText(p.error, p.spread)}));
        }
      }
      std::stable_sort(front.begin(), front.end(),
                       [](const auto& a, const auto& b) { return a.first < b.first; });
      std::string text;
      for (const auto& entry : front) text.append(text.empty() ? "" : "; ").append(entry.second);
      out << "| " << group.id << " | " << backend << " | " << text << " |\n";
    }
  }
  return out.str();
}

// ---- Sharding ----
// The partition is by run, round robin (run r goes to shard r mod n), so
// each shard gets every stepping of a sweep in turn and the shards' costs
// stay close; a run's backends stay together, so the runner's threading
// (runner.h: serial lanes per library) works within each shard unchanged.
namespace {

constexpr std::string_view kShardFormat = "talus-testbed-shard";
// Version 2 added the identity (build, settings, scenarios, digest);
// version 1 files cannot be checked against each other and are refused.
constexpr int kShardVersion = 2;

// The values of `in[key]`, an array of T; false when it is not one.
template <typename T>
bool ReadArray(const nlohmann::ordered_json& in, const char* key, std::vector<T>& out) {
  if (!in.contains(key) || !in[key].is_array()) return false;
  for (const auto& item : in[key]) {
    if constexpr (std::is_same_v<T, std::string>) {
      if (!item.is_string()) return false;
    } else if constexpr (std::is_integral_v<T>) {
      if (!item.is_number_integer()) return false;
    } else {
      if (!item.is_number()) return false;
    }
    out.push_back(item.get<T>());
  }
  return true;
}

std::string ListText(const std::vector<double>& values) {
  std::string text;
  for (double v : values) {
    char number[32];
    // Shortest round-trip form: 0.05, not 0.050000000000000003.
    const auto end = std::to_chars(number, number + sizeof number, v).ptr;
    text.append(text.empty() ? "" : ",").append(number, end);
  }
  return text;
}

std::string ListText(const std::vector<int>& values) {
  std::string text;
  for (int v : values) text.append(text.empty() ? "" : ",").append(std::to_string(v));
  return text;
}

std::string ListText(const std::vector<std::string>& values) {
  std::string text;
  for (const std::string& v : values) text.append(text.empty() ? "" : ",").append(v);
  return text;
}

// Why `shard` cannot be merged with `first`, or "" when they are of one
// partition; `name` and `firstName` label them ("shard 1/4").
std::string PartitionMismatch(const ShardFile& shard, const std::string& name, const ShardFile& first,
                              const std::string& firstName) {
  const auto differ = [&](const std::string& what, const std::string& mine, const std::string& theirs) {
    return Concat({name, " has ", what, " ", Quoted(mine), " but ", firstName, " has ", Quoted(theirs)});
  };
  const ShardIdentity& a = shard.identity;
  const ShardIdentity& b = first.identity;
  if (shard.shard.count != first.shard.count) {
    return Concat({name, " is one of ", std::to_string(shard.shard.count), " shards but ", firstName,
                   " one of ", std::to_string(first.shard.count)});
  }
  if (a.build != b.build) return differ("build", a.build, b.build) + " (merge shards of one build)";
  if (a.timeSteps != b.timeSteps) return differ("time steps", ListText(a.timeSteps), ListText(b.timeSteps));
  if (a.iterations != b.iterations) {
    return differ("iterations", ListText(a.iterations), ListText(b.iterations));
  }
  if (shard.results.backends != first.results.backends) {
    return differ("backends", ListText(shard.results.backends), ListText(first.results.backends));
  }
  if (shard.results.deterministic != first.results.deterministic) {
    return differ("--deterministic", shard.results.deterministic ? "on" : "off",
                  first.results.deterministic ? "on" : "off");
  }
  if (a.perturbCopies != b.perturbCopies || a.perturbation != b.perturbation) {
    return differ(
        "perturbed copies (count, m)",
        Concat({std::to_string(a.perturbCopies), ", ", ListText(std::vector<double>{a.perturbation})}),
        Concat({std::to_string(b.perturbCopies), ", ", ListText(std::vector<double>{b.perturbation})}));
  }
  for (const std::string& scenario : a.scenarios) {
    if (std::find(b.scenarios.begin(), b.scenarios.end(), scenario) == b.scenarios.end()) {
      return Concat({name, " ran scenario ", Quoted(scenario), ", which ", firstName, " did not"});
    }
  }
  for (const std::string& scenario : b.scenarios) {
    if (std::find(a.scenarios.begin(), a.scenarios.end(), scenario) == a.scenarios.end()) {
      return Concat({firstName, " ran scenario ", Quoted(scenario), ", which ", name, " did not"});
    }
  }
  if (a.runsDigest != b.runsDigest || shard.runCount != first.runCount) {
    return Concat(
        {name, " and ", firstName, " ran the same scenario names with different contents (runs digest ",
         a.runsDigest, " and ", b.runsDigest, ", ", std::to_string(shard.runCount), " and ",
         std::to_string(first.runCount), " runs): the scenario files differ between their machines"});
  }
  return {};
}

Result<int> ParseInt(std::string_view text, std::string_view whole) {
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || text.empty()) {
    return Error{Concat({"shard \"", whole, "\": expected i/n with integers 0 <= i < n"})};
  }
  return value;
}

}  // namespace

Result<Shard> ParseShard(std::string_view text) {
  const auto slash = text.find('/');
  if (slash == std::string_view::npos) return Error{Concat({"shard \"", text, "\": expected i/n"})};
  auto index = ParseInt(text.substr(0, slash), text);
  if (!index) return index.GetError();
  auto count = ParseInt(text.substr(slash + 1), text);
  if (!count) return count.GetError();
  if (count.Value() < 1 || index.Value() < 0 || index.Value() >= count.Value()) {
    return Error{Concat({"shard \"", text, "\": need 0 <= i < n"})};
  }
  return Shard{index.Value(), count.Value()};
}

std::vector<int> ShardRuns(int runCount, Shard shard) {
  std::vector<int> runs;
  for (int r = shard.index; r < runCount; r += shard.count) runs.push_back(r);
  return runs;
}

std::string ShardToJson(const ShardFile& shard) {
  nlohmann::ordered_json out;
  out["format"] = kShardFormat;
  out["version"] = kShardVersion;
  out["shard"] = shard.shard.index;
  out["count"] = shard.shard.count;
  out["build"] = shard.identity.build;
  out["timeSteps"] = shard.identity.timeSteps;
  out["iterations"] = shard.identity.iterations;
  out["scenarios"] = shard.identity.scenarios;
  out["runsDigest"] = shard.identity.runsDigest;
  out["perturbCopies"] = shard.identity.perturbCopies;
  out["perturbation"] = shard.identity.perturbation;
  out["runCount"] = shard.runCount;
  out["runIndices"] = shard.runIndices;
  if (!shard.resultCounts.empty()) out["resultCounts"] = shard.resultCounts;
  out["results"] = nlohmann::ordered_json::parse(ResultsToJson(shard.results));
  return out.dump(2) + "\n";
}

Result<ShardFile> ShardFromJson(std::string_view text) {
  nlohmann::ordered_json in = nlohmann::ordered_json::parse(text, nullptr, false);
  if (in.is_discarded() || !in.is_object()) return Error{"shard file: not JSON"};
  if (in.value("format", std::string()) != kShardFormat) {
    return Error{Concat({"shard file: \"format\" is not \"", kShardFormat, "\""})};
  }
  if (in.value("version", 0) != kShardVersion) {
    return Error{
        Concat({"shard file: version ", in.contains("version") ? in["version"].dump() : "(none)",
                ", expected ", std::to_string(kShardVersion),
                " (re-run the shard with this build: older files carry no build or scenario identity)"})};
  }
  for (const char* key : {"shard", "count", "runCount"}) {
    if (!in.contains(key) || !in[key].is_number_integer()) {
      return Error{Concat({"shard file: missing integer \"", key, "\""})};
    }
  }
  if (!in.contains("runIndices") || !in["runIndices"].is_array() || !in.contains("results")) {
    return Error{"shard file: missing \"runIndices\" or \"results\""};
  }
  ShardFile shard;
  if (!in.contains("build") || !in["build"].is_string() || !in.contains("runsDigest") ||
      !in["runsDigest"].is_string()) {
    return Error{"shard file: missing string \"build\" or \"runsDigest\""};
  }
  shard.identity.build = in["build"].get<std::string>();
  shard.identity.runsDigest = in["runsDigest"].get<std::string>();
  // Shard files written before the noise floor ran no copies.
  if (in.contains("perturbCopies") || in.contains("perturbation")) {
    if (!in.contains("perturbCopies") || !in["perturbCopies"].is_number_integer() ||
        !in.contains("perturbation") || !in["perturbation"].is_number()) {
      return Error{"shard file: \"perturbCopies\" (integer) and \"perturbation\" (number) go together"};
    }
    shard.identity.perturbCopies = in["perturbCopies"].get<int>();
    shard.identity.perturbation = in["perturbation"].get<double>();
  }
  if (!ReadArray(in, "timeSteps", shard.identity.timeSteps) ||
      !ReadArray(in, "iterations", shard.identity.iterations) ||
      !ReadArray(in, "scenarios", shard.identity.scenarios)) {
    return Error{
        "shard file: \"timeSteps\", \"iterations\" and \"scenarios\" must be arrays of numbers, "
        "integers and strings"};
  }
  // Bounded before anything is sized by them: a partition has at most
  // kMaxRuns runs and shards (a forged count must not make the merge
  // allocate gigabytes).
  const auto inRange = [&](const char* key, long long low, long long high) {
    const long long value = in[key].get<long long>();
    return value >= low && value <= high;
  };
  const auto maxRuns = static_cast<long long>(kMaxRuns);
  if (!inRange("runCount", 0, maxRuns) || !inRange("count", 1, maxRuns) ||
      !inRange("shard", 0, in["count"].get<long long>() - 1)) {
    return Error{Concat({"shard file: need 0 <= shard < count and count, runCount <= ",
                         std::to_string(kMaxRuns), "; got shard ", in["shard"].dump(), ", count ",
                         in["count"].dump(), ", runCount ", in["runCount"].dump()})};
  }
  shard.shard = {in["shard"].get<int>(), in["count"].get<int>()};
  shard.runCount = in["runCount"].get<int>();
  for (const auto& index : in["runIndices"]) {
    if (!index.is_number_integer()) return Error{"shard file: runIndices must be integers"};
    shard.runIndices.push_back(index.get<int>());
  }
  if (in.contains("resultCounts")) {
    if (!in["resultCounts"].is_array()) return Error{"shard file: resultCounts must be an array"};
    for (const auto& count : in["resultCounts"]) {
      if (!count.is_number_integer()) return Error{"shard file: resultCounts must be integers"};
      shard.resultCounts.push_back(count.get<int>());
    }
  }
  auto results = ResultsFromJson(in["results"].dump());
  if (!results) return Error{Concat({"shard file: ", results.GetError().message})};
  shard.results = std::move(results).Value();
  return shard;
}

Result<ResultsFile> MergeShards(const std::vector<ShardFile>& shards) {
  if (shards.empty()) return Error{"merge: no shards"};
  const ShardFile& first = shards.front();
  const std::size_t backends = first.results.backends.size();
  if (backends == 0) return Error{"merge: shard has no backends"};
  // Each run's results, in the runner's order; a run of no shard stays null.
  std::vector<std::optional<std::vector<const RunResult*>>> byRun(static_cast<std::size_t>(first.runCount));
  std::vector<int> seenShards(static_cast<std::size_t>(first.shard.count), 0);
  for (const ShardFile& shard : shards) {
    const std::string name =
        Concat({"shard ", std::to_string(shard.shard.index), "/", std::to_string(shard.shard.count)});
    const std::string firstName =
        Concat({"shard ", std::to_string(first.shard.index), "/", std::to_string(first.shard.count)});
    if (const std::string mismatch = PartitionMismatch(shard, name, first, firstName); !mismatch.empty()) {
      return Error{TidyMessage(Concat({"merge: ", mismatch}))};
    }
    if (shard.shard.index < 0 || shard.shard.index >= shard.shard.count) {
      return Error{Concat({"merge: ", name, ": index out of range"})};
    }
    if (seenShards[shard.shard.index]++ > 0) return Error{Concat({"merge: ", name, " given twice"})};
    std::vector<int> counts = shard.resultCounts;
    if (counts.empty()) counts.assign(shard.runIndices.size(), static_cast<int>(backends));
    std::size_t total = 0;
    bool countsFit = counts.size() == shard.runIndices.size();
    for (int count : counts) {
      countsFit = countsFit && count >= 0 && static_cast<std::size_t>(count) <= backends;
      total += static_cast<std::size_t>(std::max(count, 0));
    }
    if (shard.runIndices != ShardRuns(shard.runCount, shard.shard) || !countsFit ||
        shard.results.results.size() != total) {
      return Error{Concat({"merge: ", name, ": its runs are not the partition's"})};
    }
    std::size_t next = 0;
    for (std::size_t k = 0; k < shard.runIndices.size(); ++k) {
      auto& slot = byRun[static_cast<std::size_t>(shard.runIndices[k])].emplace();
      for (int b = 0; b < counts[k]; ++b) slot.push_back(&shard.results.results[next++]);
    }
  }
  for (int i = 0; i < first.shard.count; ++i) {
    if (seenShards[i] == 0) {
      return Error{
          Concat({"merge: shard ", std::to_string(i), "/", std::to_string(first.shard.count), " missing"})};
    }
  }
  ResultsFile merged;
  merged.backends = first.results.backends;
  merged.deterministic = first.results.deterministic;
  for (const auto& run : byRun) {
    for (const RunResult* result : *run) merged.results.push_back(*result);
  }
  return merged;
}

}  // namespace talus::harness
