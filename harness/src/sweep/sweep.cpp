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

nlohmann::ordered_json FamilyVerdictJson(const FamilyVerdict& verdict) {
  nlohmann::ordered_json out;
  out["outcome"] = FamilyOutcomeName(verdict.outcome);
  out["matchedCost"] = verdict.matchedCost;
  out["budgets"] = verdict.budgets;
  out["members"] = nlohmann::ordered_json::array();
  for (const FamilyPoints& family : verdict.families)
    out["members"].push_back({{"family", family.family}, {"backends", family.backends}});
  out["peers"] = nlohmann::ordered_json::array();
  for (const FamilyMargin& peer : verdict.peers) {
    out["peers"].push_back({{"family", peer.family},
                            {"atOrBelow", peer.atOrBelow},
                            {"worstBudget", peer.budget},
                            {"talusError", JsonNumber(peer.talusError)},
                            {"peerError", JsonNumber(peer.peerError)},
                            {"margin", JsonNumber(peer.margin)},
                            {"floor", JsonNumber(peer.floor)}});
  }
  return out;
}

// How many instances the family verdict judged (Talus and a peer both have
// results) and in how many Talus's family was at or below every peer.
struct FamilyCount {
  int atOrBelow = 0;
  int judged = 0;
  int notJudged = 0;
};
FamilyCount CountFamilyVerdicts(const std::vector<SweepGroup>& groups) {
  FamilyCount count;
  for (const SweepGroup& group : groups) {
    const FamilyOutcome outcome = group.families.outcome;
    if (outcome == FamilyOutcome::kNoTalus || outcome == FamilyOutcome::kNoPeer) {
      ++count.notJudged;
      continue;
    }
    ++count.judged;
    if (outcome == FamilyOutcome::kAtOrBelow) ++count.atOrBelow;
  }
  return count;
}

}  // namespace

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

double RunCost(const RunResult& result) { return result.wallSecondsPerStepMedian * result.steps; }

// Sort by (cost, error, index), then keep each point whose error is below
// every cheaper point's: the classic staircase sweep, O(n log n).
std::vector<int> ParetoFront(const std::vector<CostErrorPoint>& points) {
  std::vector<int> order(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    if (points[a].cost != points[b].cost) return points[a].cost < points[b].cost;
    return points[a].error < points[b].error;
  });
  std::vector<int> front;
  double best = kInfinity;
  for (int i : order) {
    if (points[i].error < best) {
      front.push_back(i);
      best = points[i].error;
    }
  }
  return front;
}

const CostErrorPoint* FrontPointAt(const std::vector<CostErrorPoint>& points, double budget) {
  const CostErrorPoint* best = nullptr;
  for (const CostErrorPoint& point : points) {
    if (point.cost <= budget && (best == nullptr || point.error < best->error)) best = &point;
  }
  return best;
}

double FrontErrorAt(const std::vector<CostErrorPoint>& points, double budget) {
  const CostErrorPoint* point = FrontPointAt(points, budget);
  return point != nullptr ? point->error : kInfinity;
}

double NoiseFloor(const CostErrorPoint* a, const CostErrorPoint* b) {
  // The larger spread, not their sum: a difference one of the two points
  // already showed between round-off copies of itself is no evidence, and
  // the larger of the two is the smallest floor that says so. The sum
  // (both moving apart at once) would be a worst case never observed.
  return std::max(a != nullptr ? a->spread : 0.0, b != nullptr ? b->spread : 0.0);
}

bool ErrorsTie(double a, double b, double floor) { return a == b || std::abs(a - b) <= floor; }

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
    // The smallest error wins the budget unless another front's value ties
    // with it under the two points' noise floor.
    int best = -1;
    double bestError = kInfinity;
    for (std::size_t f = 0; f < fronts.size(); ++f) {
      at[f] = FrontPointAt(fronts[f], budget);
      const double error = at[f] != nullptr ? at[f]->error : kInfinity;
      if (best < 0 || error < bestError) {
        best = static_cast<int>(f);
        bestError = error;
      }
    }
    bool tie = false;
    for (std::size_t f = 0; f < fronts.size(); ++f) {
      if (static_cast<int>(f) == best) continue;
      const double error = at[f] != nullptr ? at[f]->error : kInfinity;
      tie = tie || ErrorsTie(error, bestError, NoiseFloor(at[f], at[best]));
    }
    // An infinite error never wins (nothing was measured).
    if (best >= 0 && !tie && bestError < kInfinity) ++comparison.wins[best];
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

std::string_view FamilyOutcomeName(FamilyOutcome outcome) {
  switch (outcome) {
    case FamilyOutcome::kAtOrBelow:
      return "at or below every peer";
    case FamilyOutcome::kAbove:
      return "above a peer";
    case FamilyOutcome::kNoTalus:
      return "no Talus result";
    case FamilyOutcome::kNoPeer:
      return "no peer result";
  }
  return "?";
}

FamilyVerdict CompareFamilies(std::vector<FamilyPoints> families, std::string_view talus) {
  FamilyVerdict verdict;
  verdict.families = std::move(families);
  std::vector<std::vector<CostErrorPoint>> fronts;
  int talusIndex = -1;
  for (std::size_t f = 0; f < verdict.families.size(); ++f) {
    const FamilyPoints& family = verdict.families[f];
    // A family without points (every run failed or had no truth) has no
    // front and is not a peer that anything could be compared with.
    if (family.points.empty()) continue;
    if (family.family == talus) talusIndex = static_cast<int>(fronts.size());
    std::vector<CostErrorPoint> front;
    for (int i : ParetoFront(family.points)) front.push_back(family.points[i]);
    if (front.empty()) {
      // Every error infinite (never measured): the family still ran, so its
      // cheapest run stands for it, infinite at every budget, rather than
      // leaving no front and no budget to compare at.
      front.push_back(*std::min_element(
          family.points.begin(), family.points.end(),
          [](const CostErrorPoint& a, const CostErrorPoint& b) { return a.cost < b.cost; }));
    }
    fronts.push_back(std::move(front));
  }
  if (talusIndex < 0) return verdict;  // kNoTalus
  if (fronts.size() < 2) {
    verdict.outcome = FamilyOutcome::kNoPeer;
    return verdict;
  }
  const std::vector<double> budgets = ComparedBudgets(fronts, verdict.matchedCost);
  verdict.budgets = static_cast<int>(budgets.size());
  verdict.outcome = FamilyOutcome::kAtOrBelow;
  int front = 0;
  for (const FamilyPoints& family : verdict.families) {
    if (family.points.empty()) continue;
    const int index = front++;
    if (index == talusIndex) continue;
    FamilyMargin margin;
    margin.family = family.family;
    margin.margin = -kInfinity;
    double worstExcess = -kInfinity;
    bool first = true;
    for (double budget : budgets) {
      const CostErrorPoint* talusPoint = FrontPointAt(fronts[talusIndex], budget);
      const CostErrorPoint* peerPoint = FrontPointAt(fronts[index], budget);
      const double mine = talusPoint != nullptr ? talusPoint->error : kInfinity;
      const double theirs = peerPoint != nullptr ? peerPoint->error : kInfinity;
      // Equal errors (inf against inf included) are a tie, which the
      // criterion counts as at or below; so is a difference within the
      // noise floor (excess <= 0). Floor 0: the exact comparison.
      const double difference = mine == theirs ? 0.0 : mine - theirs;
      const double floor = NoiseFloor(talusPoint, peerPoint);
      const double excess = std::isnan(difference - floor) ? 0.0 : difference - floor;  // inf - inf: a tie
      if (first || excess > worstExcess) {
        first = false;
        worstExcess = excess;
        margin.margin = difference;
        margin.floor = floor;
        margin.budget = budget;
        margin.talusError = mine;
        margin.peerError = theirs;
      }
    }
    // The largest excess over the floor decides: above at some budget
    // exactly when it is positive (no budgets: -inf, nothing to be above at).
    margin.atOrBelow = worstExcess <= 0.0;
    if (!margin.atOrBelow) verdict.outcome = FamilyOutcome::kAbove;
    verdict.peers.push_back(std::move(margin));
  }
  return verdict;
}

std::vector<SweepGroup> AnalyseSweep(const ResultsFile& file, const std::vector<std::string>& singleSetting) {
  std::vector<SweepGroup> groups;
  std::map<std::string, std::size_t> groupIndex;
  for (const RunResult& result : file.results) {
    const double error = RunErrorScalar(result);
    if (std::isnan(error)) continue;
    const std::string id = InstanceId(result);
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
    curve->timeSteps.push_back(result.timeStep);
    curve->points.push_back({RunCost(result), error, result.perturbed.errorSpread});
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
      fronts.push_back(std::move(front));
    }
    group.comparison = CompareFronts(fronts);
    // Families in the order their first backend appears; each holds the
    // union of its variants' points.
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
  out["version"] = 1;
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
        points.push_back({{"timeStep", curve.timeSteps[k]},
                          {"cost", curve.points[k].cost},
                          {"error", JsonNumber(curve.points[k].error)},
                          {"spread", JsonNumber(curve.points[k].spread)},
                          {"front", static_cast<bool>(curve.onFront[k])}});
      }
      g["curves"].push_back({{"backend", curve.backend},
                             {"family", curve.family},
                             {"iterations", curve.iterations},
                             {"points", points}});
    }
    out["groups"].push_back(g);
  }
  const FamilyCount count = CountFamilyVerdicts(groups);
  out["familyVerdict"] = {{"talusFamily", kTalusFamily},
                          {"atOrBelowEveryPeer", count.atOrBelow},
                          {"judged", count.judged},
                          {"notJudged", count.notJudged}};
  return out.dump(2) + "\n";
}

std::string SweepMarkdown(const std::vector<SweepGroup>& groups) {
  std::ostringstream out;
  out << "## Run time against error\n\n"
      << "Error: the largest |error| / tolerance over a run's metrics with a tolerance (1 = at the "
         "tolerance, inf = "
         "not measured). Cost: wall seconds of the run. Most accurate at equal cost: most wins over the "
         "budgets at or above the matched cost (docs/testbed-sweeps.md). Spread: the noise floor, max - min "
         "of a point's error over its run and its perturbed copies (initial positions moved by round-off); "
         "two errors closer than the larger spread tie.\n\n"
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
  const FamilyCount count = CountFamilyVerdicts(groups);
  out << "\n### Talus's engine family against every peer family\n\n"
      << "A family is every variant of one engine (talus, talus-split...; bullet, bullet-f32...); its "
         "front is the Pareto front of all its variants' points. Talus is at or below a peer family when "
         "at every budget from the matched cost up Talus's best error <= the peer's or ties with it: a "
         "margin "
         "(Talus - peer) no larger than the floor (the larger spread of the two points compared; 0 without "
         "perturbed copies, then the comparison is exact) is a tie. Worst budget: where margin - floor is "
         "largest (<= 0 everywhere means at or below).\n\n"
      << "Talus at or below every peer family: " << count.atOrBelow << " of " << count.judged << " instances";
  if (count.notJudged > 0) out << " (" << count.notJudged << " more without both Talus and a peer result)";
  out << ".\n\n| scenario | verdict | budgets | peer family: worst budget s, Talus error, peer error, "
         "margin, floor "
         "|\n"
      << "|---|---|---|---|\n";
  for (const SweepGroup& group : groups) {
    const FamilyVerdict& v = group.families;
    std::string peers;
    for (const FamilyMargin& peer : v.peers) {
      peers.append(peers.empty() ? "" : "; ")
          .append(peer.family)
          .append(peer.atOrBelow ? "" : " (above)")
          .append(": ")
          .append(Number(peer.budget))
          .append(", ")
          .append(Number(peer.talusError))
          .append(", ")
          .append(Number(peer.peerError))
          .append(", ")
          .append(Number(peer.margin))
          .append(", ")
          .append(Number(peer.floor));
    }
    out << "| " << group.id << " | " << FamilyOutcomeName(v.outcome) << " | " << v.budgets << " | "
        << (peers.empty() ? "-" : peers) << " |\n";
  }
  out << "\n### Pareto fronts (time step s, iterations: cost s, error)\n\n| scenario | backend | front |\n"
      << "|---|---|---|\n";
  for (const SweepGroup& group : groups) {
    for (const std::string& backend : group.backends) {
      std::vector<std::pair<double, std::string>> front;
      for (const SweepCurve& curve : group.curves) {
        if (curve.backend != backend) continue;
        for (std::size_t k = 0; k < curve.points.size(); ++k) {
          if (!curve.onFront[k]) continue;
          front.emplace_back(curve.points[k].cost,
                             Concat({"h ", Number(curve.timeSteps[k]), ", it ",
                                     std::to_string(curve.iterations), ": ", Number(curve.points[k].cost),
                                     ", ", ErrorText(curve.points[k].error, curve.points[k].spread)}));
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
