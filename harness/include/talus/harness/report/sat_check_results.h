// The SAT validation results (`talus-sat-check --json FILE`) as the
// comparison report reads them. The harness does not link the sat-check
// program: it reads the JSON layout documented in
// docs/collision-validation.md ("JSON format"), keeping what the report
// shows (settings, truth counts, each method's verdict counts, error and
// time distributions and worst cases) and ignoring the per-pair records.
// Reading validates every field it keeps: a missing field, a wrong type, a
// negative count or a non-finite or negative measure is refused with its
// JSON path; a summary is never half-read.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "talus/result.h"

namespace talus::harness {

/// Percentiles of one measure over the pairs where it applies.
struct SatDistribution {
  int count = 0;     ///< pairs measured, >= 0 (0: the other fields are meaningless)
  double p50 = 0.0;  ///< median, in the measure's unit (m, rad or ns), >= 0
  double p90 = 0.0;  ///< 90th percentile, >= 0
  double p99 = 0.0;  ///< 99th percentile, >= 0
  double max = 0.0;  ///< largest value, >= 0
};

/// One pair where a method stands out.
struct SatCase {
  int pair = 0;                     ///< index of the pair in the generated set, >= 0
  std::string configuration;        ///< shapes, sizes, placement and alignment, as text
  double trueSignedDistance = 0.0;  ///< m; negative = penetrating
  bool methodIntersecting = false;  ///< the method's verdict
  double value = 0.0;               ///< the error that ranks the case (m or rad)
};

/// One method's results (a Talus SAT mode, a libccd or a Bullet query).
struct SatMethod {
  std::string name;    ///< e.g. "talus-pruned-clipped-cached"
  std::string family;  ///< "talus", "libccd" or "bullet"
  bool givesDepth = false;
  int agree = 0;                       ///< verdicts equal to the truth's
  int disagree = 0;                    ///< wrong verdicts outside the touching band
  int touchingBandDisagree = 0;        ///< differing verdicts inside the band (accepted)
  int oracleFailures = 0;              ///< peer errors, NaNs or missing answers
  SatDistribution depthError;          ///< |d - d*| (m)
  SatDistribution normalAngle;         ///< angle to the true normal (rad)
  SatDistribution normalExcess;        ///< overlap along the normal minus the true depth (m)
  SatDistribution timeNs;              ///< time per query (ns)
  std::vector<SatCase> disagreements;  ///< every wrong verdict outside the band
  std::vector<SatCase> worstDepth;     ///< largest depth errors first
  std::vector<SatCase> worstNormal;    ///< largest normal angles first
};

/// What the report shows of a sat-check run.
struct SatCheckSummary {
  int pairs = 0;              ///< pairs generated (settings.pairs)
  long long seed = 0;         ///< generator seed
  double touchingBand = 0.0;  ///< m, |true distance| below which either verdict is accepted
  int pairCount = 0;          ///< pairs checked
  std::vector<std::pair<std::string, int>> placements;  ///< placement name, pair count (file order)
  std::vector<std::pair<std::string, int>> alignments;  ///< alignment name, pair count (file order)
  int truthIntersecting = 0;                            ///< pairs the exact truth calls intersecting
  int truthTouchingBand = 0;                            ///< pairs inside the touching band
  int qhullChecks = 0;                                  ///< Minkowski hulls cross-checked with qhull
  int qhullMismatches = 0;                              ///< of which disagreed
  std::vector<SatMethod> methods;                       ///< at least one, in the file's order
};

/// Reads the sat-check JSON text; `source` names it in errors (a path).
Result<SatCheckSummary> ParseSatCheckJson(std::string_view text, std::string_view source);

/// Reads the sat-check JSON file at `path`; errors name the file.
Result<SatCheckSummary> ReadSatCheckFile(const std::filesystem::path& path);

/// The report's Markdown section "SAT validation": a verdict table
/// (agreement rate per method), a table of error and time percentiles, and
/// the worst cases with their configurations. summary.md appends it.
std::string SatCheckMarkdown(const SatCheckSummary& summary);

/// The same section in HTML with its plots (report_html_sat.cpp): depth
/// error and normal angle percentiles per method (log scale), and median
/// time per query against median depth error per method (log-log). Needs
/// the page's Chart.js; report.html inserts it with one call.
std::string SatCheckHtmlSection(const SatCheckSummary& summary);

}  // namespace talus::harness
