// The sweep analysis as Markdown, for sweep.md and summary.md
// (sweep_text.h).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "support/text_util.h"
#include "talus/harness/sweep/sweep_text.h"

namespace talus::harness {
namespace {

std::string CellNumber(double value) {
  if (std::isnan(value)) return "-";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return FormatNumber(value, 3);
}

// An error with its noise floor when it has one: "0.5 (spread 0.02)", the
// error moved by 0.02 between the point's perturbed copies (max - min).
std::string ErrorText(double error, double spread) {
  return spread > 0.0 ? Concat({CellNumber(error), " (spread ", CellNumber(spread), ")"}) : CellNumber(error);
}

// A point's error range: "0.5" without copies or when they agree, else
// "0.5 [0.4, 0.9]" (the unperturbed run's, then best and worst copy).
std::string RangeText(double best, double worst) {
  return best == worst ? CellNumber(worst) : Concat({"[", CellNumber(best), ", ", CellNumber(worst), "]"});
}

// Per group the backend most accurate at equal cost, the matched cost,
// each backend's error there and its budgets won.
void WinnersTable(std::ostringstream& out, const std::vector<SweepGroup>& groups) {
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
        << " | " << CellNumber(c.matchedCost) << " | " << errors << " | " << wins << " of " << c.budgets
        << " |\n";
  }
}

// Per pair of families, over every group: better, tie (split), worse.
void FamilyTallyTable(std::ostringstream& out, const std::vector<SweepGroup>& groups) {
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
}

// Per group each family pair's verdict, the budget it shows and the cost
// ratios.
void FamilyPairsTable(std::ostringstream& out, const std::vector<SweepGroup>& groups) {
  out << "\n| scenario | first | against | verdict | budgets won (first, second, of) | at budget s: first "
         "error, second error | cost ratio (first for second's error, second for first's) |\n"
      << "|---|---|---|---|---|---|---|\n";
  for (const SweepGroup& group : groups) {
    for (const FamilyPair& pair : group.families.pairs) {
      out << "| " << group.id << " | " << pair.first << " | " << pair.second << " | "
          << PairOutcomeName(pair.outcome) << (pair.split ? " (split)" : "") << " | " << pair.firstWins
          << ", " << pair.secondWins << ", " << pair.budgets << " | " << CellNumber(pair.budget) << ": "
          << RangeText(pair.firstBest, pair.firstWorst) << ", "
          << RangeText(pair.secondBest, pair.secondWorst) << " | " << CellNumber(pair.firstCostRatio) << ", "
          << CellNumber(pair.secondCostRatio) << " |\n";
    }
  }
}

// Per group each backend's front points by increasing cost.
void FrontsTable(std::ostringstream& out, const std::vector<SweepGroup>& groups) {
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
          front.emplace_back(p.cost, Concat({"h ", CellNumber(curve.timeSteps[k]), ", it ",
                                             std::to_string(curve.iterations), ": ", CellNumber(p.cost), ", ",
                                             CellNumber(p.longestStep), ", ", ErrorText(p.error, p.spread)}));
        }
      }
      std::stable_sort(front.begin(), front.end(),
                       [](const auto& a, const auto& b) { return a.first < b.first; });
      std::string text;
      for (const auto& entry : front) text.append(text.empty() ? "" : "; ").append(entry.second);
      out << "| " << group.id << " | " << backend << " | " << text << " |\n";
    }
  }
}

}  // namespace

std::string SweepMarkdown(const std::vector<SweepGroup>& groups) {
  std::ostringstream out;
  WinnersTable(out, groups);
  FamilyTallyTable(out, groups);
  FamilyPairsTable(out, groups);
  FrontsTable(out, groups);
  return out.str();
}

}  // namespace talus::harness
