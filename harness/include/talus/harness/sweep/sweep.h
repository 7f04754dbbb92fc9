// Run time against error: the analysis of a stepping sweep (the same runs
// at several time steps and solver iterations, runner.h ExpandStepping),
// and the sharding of long job lists.
//
// Each result of a scenario instance with a truth gives one (cost, error)
// point: cost is the run's total wall time (RunResult::wallSeconds, never a
// median over its steps), error the run's error scalar (RunErrorScalar);
// a run that failed is a point too, infinitely bad at its cost. With
// perturbed copies a point also carries its best and worst error over the
// run and its copies. Points group into curves, one per (scenario
// instance, backend, iterations); each backend's Pareto front is marked,
// per instance the backend most accurate at equal cost is named
// (CompareFronts), and every engine family is judged against every other
// (CompareFamilies: better, tie or worse; definitions in
// docs/testbed-sweeps.md). Everything is a pure function of the results,
// in their order, so equal results give equal text.
//
// Sharding: a job is one (run, backend); shard i of n takes every job of
// the runs whose index r (in the expanded run list) has r mod n == i, so
// the n shards cover every job exactly once and MergeShards puts them back
// in the unsharded order.
#pragma once

#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "talus/harness/run/results_file.h"
#include "talus/harness/scenario/scenario.h"
#include "talus/result.h"

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

/// The analysis as JSON (2-space indented, infinities as null) and as a
/// Markdown section (per group: the winner, wins, error at the matched
/// cost; the family tallies; per group each family pair's verdict; each
/// backend's front with cost and longest step).
std::string SweepToJson(const std::vector<SweepGroup>& groups);
std::string SweepMarkdown(const std::vector<SweepGroup>& groups);

/// The report.html section of a results file holding a stepping sweep
/// (runs with "h" sweep values): log-log charts, one per group, one
/// dataset per curve, fronts drawn as dashed lines. Empty when there is no
/// sweep. Uses the page's Chart.js.
std::string SweepHtmlSection(const ResultsFile& file);

/// A shard specification "i/n" (0 <= i < n); an Error names the text.
struct Shard {
  int index = 0;
  int count = 1;
};
Result<Shard> ParseShard(std::string_view text);

/// The run indices of shard `shard` among `runCount` runs (r mod n == i).
std::vector<int> ShardRuns(int runCount, Shard shard);

/// What every shard of one partition must share besides its backends and
/// deterministic mode (which its results file holds): the build that ran
/// it, the sweep's stepping settings and the runs themselves. The merge
/// compares each part and names the first that differs.
struct ShardIdentity {
  std::string build;              ///< BuildId() of the program that ran the shard
  std::vector<double> timeSteps;  ///< the sweep's time steps, s, as given
  std::vector<int> iterations;    ///< the sweep's iteration counts, as given
  /// The scenarios of the unsharded run list, first appearance order, each
  /// once (names as in the files).
  std::vector<std::string> scenarios;
  /// 16 hex digits: FNV-1a 64 over every run of the unsharded list (its id,
  /// stepping and its scenario as ScenarioToJson writes it), so two
  /// partitions agree only when every scenario file read the same.
  std::string runsDigest;
  /// The noise floor's settings (perturbed_copies.h): copies per point and
  /// metres (0 without copies); shard files without them are of 0 copies.
  int perturbCopies = 0;
  double perturbation = 0.0;
};

/// The identity of a sweep over `runs` (the unsharded, expanded list) with
/// the given settings, run by this build.
ShardIdentity MakeShardIdentity(const std::vector<Run>& runs, const std::vector<double>& timeSteps,
                                const std::vector<int>& iterations);

/// A shard's results: the results file of its runs plus where they go.
struct ShardFile {
  Shard shard;
  ShardIdentity identity;
  int runCount = 0;             ///< runs in the unsharded list
  std::vector<int> runIndices;  ///< this shard's runs, increasing
  ResultsFile results;          ///< the runs' results, run-major (the runner's order)
  /// Results per entry of runIndices: the backends that ran it (fewer than
  /// results.backends when its scenario lists backends, possibly 0). Empty
  /// means every run has one result per backend.
  std::vector<int> resultCounts;
};
std::string ShardToJson(const ShardFile& shard);
Result<ShardFile> ShardFromJson(std::string_view text);

/// The unsharded results from every shard of one partition, each run
/// exactly once; else an Error naming the shard and what is wrong: a shard
/// missing or given twice, or shards from different partitions (another
/// shard count, build, time steps, iterations, backends, deterministic
/// mode, perturbed copies, scenario set or scenario contents).
Result<ResultsFile> MergeShards(const std::vector<ShardFile>& shards);

}  // namespace talus::harness
