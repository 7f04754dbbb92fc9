// A stepping sweep's results grouped into curves per scenario instance,
// with fronts, the comparison at equal cost and the family verdicts
// (sweep_analysis.h).
#include "talus/harness/sweep/sweep_analysis.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "support/numbers.h"
#include "support/text_util.h"

namespace talus::harness {
namespace {

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

}  // namespace

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

namespace {

// The instances with a truth: some run of them measured one. A failed run
// of such an instance stays in as an infinitely bad point at its cost; a
// run of an instance without a truth has nothing to be judged on.
std::map<std::string, bool> InstancesWithTruth(const ResultsFile& file) {
  std::map<std::string, bool> hasTruth;
  for (const RunResult& result : file.results) {
    if (!std::isnan(RunErrorScalar(result))) hasTruth[InstanceId(result)] = true;
  }
  return hasTruth;
}

// The curve of `group` that `result` belongs on (its backend at its
// iterations), added when new; nullptr when the backend has a single
// setting and a curve already: its other iteration counts are dropped.
SweepCurve* CurveFor(SweepGroup& group, const RunResult& result, bool singleSetting) {
  SweepCurve* curve = nullptr;
  bool backendSeen = false;
  for (SweepCurve& c : group.curves) {
    if (c.backend != result.backend) continue;
    backendSeen = true;
    if (c.iterations == result.iterations) curve = &c;
  }
  if (curve == nullptr) {
    if (singleSetting && backendSeen) return nullptr;
    group.curves.push_back({result.backend, result.iterations, {}, {}, {}, EngineFamily(result)});
    curve = &group.curves.back();
  }
  return curve;
}

// One result's point: its cost and error, and with perturbed copies the
// range of errors and the cheapest run over it and its copies.
CostErrorPoint PointOf(const RunResult& result, double error) {
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
  }
  return point;
}

// Every result of an instance with a truth as a point on its curve, the
// groups in the order their instances first appear.
std::vector<SweepGroup> GroupIntoCurves(const ResultsFile& file,
                                        const std::vector<std::string>& singleSetting) {
  const std::map<std::string, bool> hasTruth = InstancesWithTruth(file);
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
    const bool single =
        std::find(singleSetting.begin(), singleSetting.end(), result.backend) != singleSetting.end();
    SweepCurve* curve = CurveFor(groups[found->second], result, single);
    if (curve == nullptr) continue;
    curve->timeSteps.push_back(result.timeStep);
    curve->points.push_back(PointOf(result, error));
  }
  return groups;
}

// Backend-major in the file's backend order (stable: iterations stay in
// the order they were met), and the group's backends in that order.
void OrderByBackend(SweepGroup& group, const std::vector<std::string>& fileBackends) {
  const auto rank = [&](const std::string& backend) {
    return std::find(fileBackends.begin(), fileBackends.end(), backend) - fileBackends.begin();
  };
  std::stable_sort(group.curves.begin(), group.curves.end(), [&](const SweepCurve& a, const SweepCurve& b) {
    return rank(a.backend) < rank(b.backend);
  });
  for (const SweepCurve& curve : group.curves) {
    if (group.backends.empty() || group.backends.back() != curve.backend)
      group.backends.push_back(curve.backend);
  }
}

// Each backend's Pareto front over all its curves, marked on the curves
// (onFront) and returned per backend in the group's backend order.
std::vector<std::vector<CostErrorPoint>> MarkBackendFronts(SweepGroup& group) {
  std::vector<std::vector<CostErrorPoint>> fronts;
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
  return fronts;
}

// Families in the order their first backend appears; each holds the
// union of its variants' points, failed runs included.
std::vector<FamilyPoints> FamiliesOf(const SweepGroup& group) {
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
  return families;
}

}  // namespace

std::vector<SweepGroup> AnalyseSweep(const ResultsFile& file, const std::vector<std::string>& singleSetting) {
  std::vector<SweepGroup> groups = GroupIntoCurves(file, singleSetting);
  for (SweepGroup& group : groups) {
    OrderByBackend(group, file.backends);
    group.comparison = CompareFronts(MarkBackendFronts(group));
    group.families = CompareFamilies(FamiliesOf(group));
  }
  return groups;
}

}  // namespace talus::harness
