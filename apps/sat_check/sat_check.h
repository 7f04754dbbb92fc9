// The SAT validation: every pair from the generator goes through each
// narrow-phase method (Talus's SAT in every mode, libccd, Bullet) and the
// exact Minkowski-difference truth; the report compares verdicts, depths,
// normals and contact points with the truth and times every query.
//
// The report is plain data (SatCheckReport); sat_check_report.cpp turns it
// into JSON and Markdown (docs/collision-validation.md describes both).
// Everything but the times is deterministic for a given seed.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "pair_generator.h"
#include "talus/math.h"
#include "talus/result.h"

namespace talus::validation {

/// Most pairs one run accepts. Each pair keeps its record (one answer per
/// method) for the JSON, about 2 kB; 1e6 pairs is 2 GB of report and
/// hours of qhull checks, past any use; more is refused.
inline constexpr int kMaxPairs = 1000000;

/// The gate's exactness: the depth Talus reports for its chosen axis must
/// be within this fraction of the pair's size (ShapePair::size) of the true
/// minimum, beyond the SAT's stated preference band (issue 15).
inline constexpr double kExactRelative = 1e-9;

/// Round-off allowance in units of the largest world coordinate of the
/// pair's vertices times machine epsilon. Every world vertex is rounded in
/// the transform (3 products and sums, a few ulps of the coordinate); a
/// depth or a plane distance is a difference of dot products of such
/// vertices (a few ulps more), and the truth's own Minkowski hull adds a
/// plane fit of the same order; 64 covers those with margin. Far from the
/// origin this, not kExactRelative, is the bound: a 1 mm shape at 1e5 m has
/// coordinates with an ulp of 1.5e-11 m, above 1e-9 of its size.
inline constexpr double kRoundOffUlps = 64.0;

/// What to run.
struct SatCheckSettings {
  int pairs = 2000;        ///< pairs generated, 1..kMaxPairs
  std::uint64_t seed = 1;  ///< generator seed
  /// Pairs whose true |signed distance| is below this fraction of their
  /// size (plus round-off) are in the touching band: a verdict either way
  /// is acceptable there. 1e-9, the exactness asked of depths.
  double touchingBand = 1e-9;
  /// Contact points may lie outside a shape by this fraction of the pair's
  /// size plus round-off (a point of the overlap is inside both). 1e-9.
  double pointTolerance = 1e-9;
  int timingRepeats = 3;       ///< each timed query runs this many times (>= 1); 0 turns timing off
  bool checkWithQhull = true;  ///< cross-check each Minkowski difference with qhull
  int worstCases = 5;          ///< worst cases kept per method and measure
};

/// Percentiles of a sample (all 0 when empty).
struct Distribution {
  int count = 0;
  double p50 = 0.0;
  double p90 = 0.0;
  double p99 = 0.0;
  double max = 0.0;
};

/// A pair where a method stands out, with what made the pair.
struct CaseRecord {
  int pair = 0;
  std::string configuration;        ///< Describe(pair)
  double trueSignedDistance = 0.0;  ///< metres
  bool methodIntersecting = false;
  double value = 0.0;  ///< the measure (error) that put it here
};

/// One method's distributions over the pairs of one family.
struct FamilyReport {
  std::string family;  ///< ToString(Family)
  Distribution depthError;
  Distribution normalAngle;
  Distribution normalExcess;
  Distribution pointOutside;
};

/// The results of one method over all pairs.
struct MethodReport {
  std::string name;                       ///< e.g. "talus-pruned-clipped-cached", "ccd-gjk-penetration"
  std::string family;                     ///< "talus", "libccd" or "bullet"
  bool givesDepth = false;                ///< depth and normal are reported
  bool givesPoints = false;               ///< contact points are reported
  int agree = 0;                          ///< verdict equals the truth's
  int disagree = 0;                       ///< verdict differs, outside the touching band
  int touchingBandDisagree = 0;           ///< verdict differs inside the band (acceptable)
  int oracleFailures = 0;                 ///< libccd/Bullet: error, NaN or no answer
  std::vector<CaseRecord> disagreements;  ///< every disagreement outside the band
  Distribution depthError;                ///< |depth - true depth| (m), pairs both call intersecting
  Distribution normalAngle;               ///< angle to the true normal (rad), pairs with a unique minimum
  /// Overlap of the shapes along the reported normal minus the true depth
  /// (m, >= 0): how much worse the normal is than the best, robust to ties.
  Distribution normalExcess;
  Distribution pointOutside;    ///< per contact point: distance outside the farther shape (m)
  int pointsOverTolerance = 0;  ///< points farther out of a shape than true depth + pointTolerance
  Distribution timeNs;          ///< time per query (ns)
  // The gate (Talus methods; see docs/collision-validation.md): counts of
  // pairs or points beyond the stated bounds.
  int depthOverBound = 0;      ///< |depth - true| > preference band + exact + round-off
  int normalOverBound = 0;     ///< normal excess > the same bound
  int deepestPointDeeper = 0;  ///< deepest point deeper than the manifold depth beyond round-off
  /// Measured, not gated: manifolds whose deepest point is shallower than
  /// the depth beyond round-off. The depth is the projections' overlap;
  /// when the SAT's deepest vertex lies outside the other shape no point of
  /// the intersection need be that deep (docs/collision-narrow-phase.md).
  int deepestPointShallower = 0;
  /// Points outside either shape beyond round-off; gated for the Clipped
  /// modes (issue 26: inside both shapes), measured for WriteUp.
  int pointsOutsideEither = 0;
  int pointsOutsideBoth = 0;  ///< points outside both shapes beyond tolerance (WriteUp: + its 5 mm rule)
  std::vector<FamilyReport> families;   ///< by Family
  std::vector<CaseRecord> worstDepth;   ///< largest depth errors
  std::vector<CaseRecord> worstNormal;  ///< largest normal excesses
};

/// Checks of the truth itself.
struct TruthReport {
  int qhullChecks = 0;      ///< Minkowski differences cross-checked with qhull
  int qhullMismatches = 0;  ///< of those, disagreeing (listed in the messages)
  std::vector<std::string> qhullMessages;
  int boxClosedFormChecks = 0;         ///< face-aligned box pairs checked in closed form
  double boxClosedFormMaxError = 0.0;  ///< metres, largest |truth - closed form|
  int boxClosedFormVerdictMismatches = 0;
  int intersecting = 0;  ///< pairs the truth calls intersecting
  int touchingBand = 0;  ///< pairs within the touching band
  int tiedMinimum = 0;   ///< intersecting pairs whose minimum direction is not unique
};

/// One method's answer on one pair, kept for the JSON's per-pair table.
struct PairMethodResult {
  bool ok = true;  ///< false: the oracle failed (error, NaN, no answer)
  bool intersecting = false;
  double depth = 0.0;         ///< metres (methods that give depth, when intersecting)
  double normalExcess = 0.0;  ///< metres (same)
  int points = 0;             ///< contact points given
  double timeNs = 0.0;        ///< mean time per query (0 when timing is off)
};

/// One pair: how it was made, the truth, and every method's answer (same
/// order as SatCheckReport::methods).
struct PairRecord {
  int index = 0;
  std::string configuration;
  double trueSignedDistance = 0.0;  ///< metres
  Vec3 trueNormal = Vec3::UnitY();  ///< B towards A
  std::vector<PairMethodResult> results;
};

/// The whole run.
struct SatCheckReport {
  SatCheckSettings settings;
  int pairCount = 0;
  std::vector<int> placementCounts;  ///< by Placement
  std::vector<int> alignmentCounts;  ///< by Alignment
  TruthReport truth;
  std::vector<MethodReport> methods;
  std::vector<PairRecord> pairs;
  /// One line per Talus method and bound it breaks, or error it returned;
  /// empty when all pass.
  std::vector<std::string> failures;
  /// One line per check of the truth itself that failed (qhull against the
  /// second hull builder, the box closed form); empty when the truth
  /// holds. A broken truth makes every verdict above meaningless.
  std::vector<std::string> truthBroken;
};

/// Exit statuses of talus-sat-check (main.cpp; docs/collision-validation.md).
inline constexpr int kExitPassed = 0;
inline constexpr int kExitBoundBroken = 1;  ///< a Talus mode broke a bound or returned an error
inline constexpr int kExitUsage = 2;        ///< bad arguments, or an output that could not be written
inline constexpr int kExitTruthBroken = 3;  ///< the truth disagrees with its own checks

/// The exit status for a finished report: truth broken first (nothing
/// else can be judged then), then a broken bound, else passed.
int ExitStatus(const SatCheckReport& report);

/// Runs the whole validation. Refuses bad settings (pairs outside
/// 1..kMaxPairs, negative tolerances or repeats) with a message naming the
/// field. A run that finds Talus beyond its bounds still returns a report,
/// with `failures` filled.
Result<SatCheckReport> RunSatCheck(const SatCheckSettings& settings);

/// The text of --seed as a generator seed: decimal digits only, 0 to
/// 2^64 - 1. A sign, another character or a value past 2^64 - 1 is refused
/// with the text quoted (cut to 40 bytes): a seed that wrapped or was read
/// as a different number would silently give another pair set.
Result<std::uint64_t> ParseSeed(std::string_view text);

/// The closed-form answer for two boxes with the same rotation (face
/// aligned): signed distance (m; gap > 0, minus the depth when
/// overlapping). halfA/halfB: half extents; offset: B's centre minus A's in
/// their shared frame.
double BoxPairSignedDistance(const Vec3& halfA, const Vec3& halfB, const Vec3& offset);

/// The report as JSON text (2-space indented).
std::string ReportToJson(const SatCheckReport& report);
/// The report as a Markdown section (level-2 heading "SAT validation").
std::string ReportToMarkdown(const SatCheckReport& report);
/// One line: "PASS: ...", "FAIL: n bounds broken: first failure" or
/// "TRUTH BROKEN: n checks of the truth failed: first".
std::string SummaryLine(const SatCheckReport& report);

}  // namespace talus::validation
