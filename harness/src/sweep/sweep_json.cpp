// sweep.json: the sweep analysis as JSON (sweep_text.h).
#include <cmath>
#include <nlohmann/json.hpp>

#include "support/numbers.h"
#include "talus/harness/sweep/sweep_text.h"

namespace talus::harness {
namespace {

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

}  // namespace

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
}  // namespace talus::harness
