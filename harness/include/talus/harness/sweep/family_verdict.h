// Every engine family against every other in one scenario instance:
// better, tie or worse, compared at every budget on the error axis
// (CompareAtBudget, cost_error_front.h) and on the cost axis (the cost one
// family needs for the other's best error). Definitions in
// docs/testbed-sweeps.md.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "talus/harness/run/results_file.h"
#include "talus/harness/sweep/cost_error_front.h"

namespace talus::harness {

/// Engine families: a backend's family is the engine it drives, the first
/// word of its "engine" setting ("Talus (double)" -> "Talus", "Bullet 324
/// (single precision...)" -> "Bullet"), so every variant of one engine
/// (talus, talus-split...; bullet, bullet-f32...) is one family. A result
/// without that setting is a family of its own, named by its backend.
inline constexpr std::string_view kTalusFamily = "Talus";
std::string EngineFamily(const RunResult& result);

/// One engine family's points in one scenario instance: the union of its
/// variants' points (every setting of every variant, failed runs included).
struct FamilyPoints {
  std::string family;                 ///< e.g. "Bullet"
  std::vector<std::string> backends;  ///< its variants that have points, in the results' order
  std::vector<CostErrorPoint> points;
};

/// The verdict between two families in one instance.
enum class PairOutcome { kFirstBetter, kTie, kSecondBetter };
std::string_view PairOutcomeName(PairOutcome outcome);

/// Two families compared at every budget: the cost of every point of
/// either (failed runs included), from the cheapest up, so a family that
/// has nothing that cheap, or only a crash, loses those budgets (the cost
/// axis), and at each budget CompareAtBudget (the error axis). The first
/// is better when it wins some budget and loses none; the second likewise;
/// otherwise a tie (no budget decided, or each won some: `split`).
struct FamilyPair {
  std::string first, second;
  PairOutcome outcome = PairOutcome::kTie;
  bool split = false;  ///< each won some budget (counted as a tie)
  int budgets = 0;
  int firstWins = 0, secondWins = 0;
  /// The budget shown: the first won by the better family, or, in a tie,
  /// the first won by either (the first budget when none was won).
  double budget = 0.0;
  /// Best and worst error each family's budget point reached there
  /// (+infinity: a failure or nothing that cheap).
  double firstBest = 0.0, firstWorst = 0.0, secondBest = 0.0, secondWorst = 0.0;
  /// The cost axis: the cost the first family needs to reach the second's
  /// most accurate point (its smallest worst error, the cheapest such),
  /// over that point's cost: "first needs x the cost for second's error";
  /// +infinity when the first never reaches it, NaN when the costs are 0
  /// (deterministic mode). secondCostRatio the other way round.
  double firstCostRatio = 0.0, secondCostRatio = 0.0;
};
FamilyPair CompareFamilyPair(const FamilyPoints& first, const FamilyPoints& second);

/// Every family present in one instance and every pair of them.
struct FamilyVerdict {
  std::vector<FamilyPoints> families;  ///< with points, Talus first, then in the results' order
  std::vector<FamilyPair> pairs;       ///< every pair (i < j in `families`), so Talus's come first
};

/// Compares every family with every other (families without points are
/// dropped: nothing ran with a truth). The family named `first` is moved to
/// the front, so its pairs read "first against each peer".
FamilyVerdict CompareFamilies(std::vector<FamilyPoints> families, std::string_view first = kTalusFamily);

}  // namespace talus::harness
