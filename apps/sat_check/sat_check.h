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
#include <vector>

#include "pair_generator.h"
#include "talus/math.h"
#include "talus/result.h"

namespace talus::validation {

/// What to run.
struct SatCheckSettings {
  int pairs = 2000;        ///< pairs generated, >= 1
  std::uint64_t seed = 1;  ///< generator seed
  /// Pairs whose true |signed distance| is below this (metres) are in the
  /// touching band: a verdict either way is acceptable there. 1e-6 m.
  double touchingBand = 1e-6;
  /// A contact point counts as misplaced when it lies farther than the
  /// true depth plus this (metres) outside either shape. 1e-6 m.
  double pointTolerance = 1e-6;
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
  Distribution pointOutside;            ///< per contact point: distance outside the farther shape (m)
  int pointsOverTolerance = 0;          ///< points farther out of a shape than true depth + pointTolerance
  Distribution timeNs;                  ///< time per query (ns)
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
  int intersecting = 0;    ///< pairs the truth calls intersecting
  int touchingBand = 0;    ///< pairs within the touching band
  int tiedMinimum = 0;     ///< intersecting pairs whose minimum direction is not unique
  int builderRetries = 0;  ///< pairs whose Minkowski hull needed a coarser BuildHull tolerance
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
};

/// Runs the whole validation. Refuses bad settings (pairs < 1, negative
/// tolerances or repeats) with a message naming the field.
Result<SatCheckReport> RunSatCheck(const SatCheckSettings& settings);

/// The closed-form answer for two boxes with the same rotation (face
/// aligned): signed distance (m; gap > 0, minus the depth when
/// overlapping). halfA/halfB: half extents; offset: B's centre minus A's in
/// their shared frame.
double BoxPairSignedDistance(const Vec3& halfA, const Vec3& halfB, const Vec3& offset);

/// The report as JSON text (2-space indented).
std::string ReportToJson(const SatCheckReport& report);
/// The report as a Markdown section (level-2 heading "SAT validation").
std::string ReportToMarkdown(const SatCheckReport& report);

}  // namespace talus::validation
