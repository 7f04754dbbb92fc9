// Run time against error: the analysis of a stepping sweep (the same runs
// at several time steps and solver iterations, runner.h ExpandStepping),
// and the sharding of long job lists.
//
// Each result with a truth gives one (cost, error) point: cost is its wall
// time (median seconds per step x steps), error the run's error scalar
// (RunErrorScalar). Points group into curves, one per (scenario instance,
// backend, iterations); each backend's Pareto front over all its settings
// is marked, and per scenario instance the backend most accurate at equal
// cost is named (CompareFronts, definition in docs/testbed-sweeps.md), and
// Talus's engine family is judged against every peer family (CompareFamilies:
// issue 15's "at or below every peer").
// Everything is a pure function of the results, in their order, so equal
// results give equal text.
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

/// The cost of one result: wall seconds of the whole run (median seconds
/// per step x steps); 0 in deterministic mode.
double RunCost(const RunResult& result);

/// One point of a run-time-against-error plot.
struct CostErrorPoint {
  double cost = 0.0;   ///< seconds (with perturbed copies: the median over the runs)
  double error = 0.0;  ///< error scalar, >= 0, may be +infinity (the unperturbed run's)
  double spread =
      0.0;  ///< the error's noise floor: max - min over the run and its perturbed copies; 0 without
};

/// Indices of the Pareto-optimal points (no other point has cost <= and
/// error <= with one strictly smaller), by increasing cost; of equal points
/// the first is kept. Infinite errors are never on the front unless every
/// point is infinite (then none is).
std::vector<int> ParetoFront(const std::vector<CostErrorPoint>& points);

/// The best error a front reaches for a budget: the smallest error among
/// the points with cost <= budget, +infinity when none is that cheap.
double FrontErrorAt(const std::vector<CostErrorPoint>& points, double budget);

/// The point FrontErrorAt reads: the first of smallest error among those
/// with cost <= budget; nullptr when none is that cheap.
const CostErrorPoint* FrontPointAt(const std::vector<CostErrorPoint>& points, double budget);

/// The noise floor of comparing two front values (FrontPointAt of each,
/// nullptr for none): the larger of the two points' spreads. A difference
/// of errors no larger than it is a tie: one of the two points already
/// moved that much between round-off-perturbed copies of itself.
double NoiseFloor(const CostErrorPoint* a, const CostErrorPoint* b);

/// Whether errors `a` and `b` are tied under `floor`: equal (inf with inf
/// included) or |a - b| <= floor. With floor 0 this is exact equality.
bool ErrorsTie(double a, double b, double floor);

/// Which of several fronts (one per backend) is most accurate at equal
/// cost. The compared budgets are the costs of every front point that are
/// >= the matched cost (the largest of the fronts' cheapest costs, the
/// least budget at which every backend has a result); at each budget the
/// backend with the smallest FrontErrorAt wins, unless another backend's
/// error ties with it under their NoiseFloor (then nobody wins that
/// budget). The winner is the backend with the most wins, -1 when there is
/// no budget or a tie.
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
/// variants' points (every setting of every variant).
struct FamilyPoints {
  std::string family;                 ///< e.g. "Bullet"
  std::vector<std::string> backends;  ///< its variants that have points, in the results' order
  std::vector<CostErrorPoint> points;
};

/// Talus's family against one peer family at the compared budgets.
struct FamilyMargin {
  std::string family;       ///< the peer family
  bool atOrBelow = false;   ///< at every budget Talus's best error <= the peer's or ties with it (ErrorsTie)
  double budget = 0.0;      ///< s: the budget where margin - floor is largest (the first such)
  double talusError = 0.0;  ///< Talus family's FrontErrorAt(budget)
  double peerError = 0.0;   ///< the peer family's FrontErrorAt(budget)
  double margin = 0.0;      ///< talusError - peerError (0 when equal, +inf when only the peer is finite)
  double floor = 0.0;       ///< NoiseFloor of the two points compared at `budget`
};

/// The issue-15 criterion for one scenario instance.
enum class FamilyOutcome {
  kAtOrBelow,  ///< Talus's family front at or below every peer family's at every budget
  kAbove,      ///< some peer family is strictly better at some budget
  kNoTalus,    ///< no Talus result with a truth: nothing to judge
  kNoPeer,     ///< Talus alone: nothing to compare with
};
std::string_view FamilyOutcomeName(FamilyOutcome outcome);

struct FamilyVerdict {
  FamilyOutcome outcome = FamilyOutcome::kNoTalus;
  std::vector<FamilyPoints> families;  ///< every family present, in the results' order
  double matchedCost = 0.0;            ///< s: ComparedBudgets over the families' fronts
  int budgets = 0;
  std::vector<FamilyMargin> peers;  ///< one per peer family, in `families` order
};

/// Compares the family named `talus` with every other family: each
/// family's front is the Pareto front of its points; the budgets are
/// ComparedBudgets over those fronts; at each budget the errors are
/// compared under the two points' NoiseFloor (exactly when both spreads are
/// 0), ties counting as at or below. A
/// family whose every error is infinite stands at its cheapest cost with
/// an infinite error; a family without points is skipped.
FamilyVerdict CompareFamilies(std::vector<FamilyPoints> families, std::string_view talus = kTalusFamily);

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
  FamilyVerdict families;             ///< Talus's engine family against every peer family
};

/// The backends a sweep analysis treats as having no iteration setting:
/// ODE's dWorldStep solves its LCP directly, so iterations do not apply.
inline const std::vector<std::string> kSweepSingleSetting{"ode-step", "ode-step-tuned"};

/// Groups the results with a truth into curves; backends in
/// `singleSetting` ignore iterations (e.g. "ode-step"): only their first
/// iteration count is kept.
std::vector<SweepGroup> AnalyseSweep(const ResultsFile& file, const std::vector<std::string>& singleSetting);

/// The analysis as JSON (2-space indented, infinities as null) and as a
/// Markdown section (per group: the winner, wins, error at the matched
/// cost, each backend's front; then the family verdict per group, its
/// worst budget against each peer family, and the count of instances where
/// Talus's family is at or below every peer family).
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
