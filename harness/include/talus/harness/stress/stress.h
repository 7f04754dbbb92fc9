// Stability under stress: per engine, where it breaks along each stress
// axis (the tallest box column that stands, the largest mass ratio, the
// largest time step, the farthest offset, the highest speed before
// tunnelling, the longest run before energy drifts, the smallest and
// largest body size).
//
// Every axis builds its worlds in code (stress_scenes.cpp) so every backend
// runs the same world, and states its failure criterion (StressAxisInfo).
// SearchEnvelope walks an axis geometrically from its start until the
// first failure or the limit, then bisects between the last passing and
// the first failing value. Everything is deterministic.
#pragma once

#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "talus/harness/backend/backend.h"
#include "talus/harness/scenario/scenario.h"
#include "talus/result.h"

namespace talus::harness {

/// How an envelope search walks one axis.
struct EnvelopeSearch {
  double start = 1.0;    ///< first value probed, > 0
  double factor = 2.0;   ///< > 1 walks up, in (0, 1) walks down
  double limit = 16.0;   ///< last value probed (inclusive; the walk stops beyond it)
  bool integer = false;  ///< values are integers (bisection on integers, down to adjacent ones)
  int bisections = 3;    ///< >= 0: geometric bisections between last pass and first fail (real axes)
};

/// One probed value.
struct EnvelopeProbe {
  double value = 0.0;
  bool pass = false;
  double measure = std::numeric_limits<double>::quiet_NaN();  ///< the axis's number at this value
  std::string detail;                                         ///< why it failed ("" when it passed)
};

/// Where an axis breaks: lastPass / firstFail are NaN when every probe
/// failed / passed.
struct EnvelopeResult {
  double lastPass = std::numeric_limits<double>::quiet_NaN();
  double firstFail = std::numeric_limits<double>::quiet_NaN();
  std::vector<EnvelopeProbe> probes;  ///< in probing order
};

/// The search: start, start f, start f^2, ... while within the limit, until
/// a failure; then bisection (integer midpoint, or geometric midpoint
/// `bisections` times) between the last pass and the first failure. The
/// oracle is called once per probed value.
EnvelopeResult SearchEnvelope(const EnvelopeSearch& search,
                              const std::function<EnvelopeProbe(double)>& oracle);

enum class StressAxis {
  Column,       ///< boxes in a column (integer)
  MassRatio,    ///< top / bottom mass of a two-box stack
  TimeStep,     ///< seconds per step of a 5-layer pyramid
  Offset,       ///< metres from the origin of a box rest and a box slide
  Speed,        ///< m/s of a 0.1 m box towards a 0.05 m wall
  EnergyDrift,  ///< steps of a torque-free spinning box
  SmallSize,    ///< metres: edge of a resting and sliding cube, walking down
  LargeSize,    ///< metres: same, walking up
};

/// An axis's name (as on the command line), unit, criterion and searches.
struct StressAxisInfo {
  StressAxis axis;
  std::string name;       ///< "column", "mass-ratio", ...
  std::string unit;       ///< of the values
  std::string criterion;  ///< what "pass" means, one sentence
  EnvelopeSearch ci;      ///< modest default
  EnvelopeSearch full;    ///< the on-demand search (--full)
};
const std::vector<StressAxisInfo>& StressAxes();

/// The probe of `axis` at `value` with `backend`: builds the worlds,
/// runs them and judges. A backend refusing a world is a failed probe.
EnvelopeProbe ProbeStress(const BackendRegistry& registry, const std::string& backend, StressAxis axis,
                          double value);

/// The runs of one probe (exposed for tests and inspection).
std::vector<Run> StressRuns(StressAxis axis, double value);

/// One envelope per (axis, backend).
struct StressEntry {
  std::string axis;
  std::string backend;
  EnvelopeResult envelope;
};

/// The envelope table (Markdown: a row per backend, a column per axis with
/// "last pass / first fail"), the criteria and every probe.
std::string StressMarkdown(const std::vector<StressEntry>& entries);
/// The same as JSON (NaN as null): {"format": "talus-testbed-stress",
/// "version": 1, "envelopes": [{"axis", "backend", "lastPass", "firstFail",
/// "probes": [{"value", "pass", "measure", "detail"}]}]} (stress_json.cpp).
std::string StressJson(const std::vector<StressEntry>& entries);
/// Reads what StressJson writes; `source` names the text in messages. Every
/// field is checked (format and version, types, finite probe values); the
/// first problem is an Error naming its JSON path.
Result<std::vector<StressEntry>> ParseStressJson(std::string_view text, std::string_view source);
/// The same, from a file (stress.json of `talus-testbed stress`).
Result<std::vector<StressEntry>> ReadStressFile(const std::filesystem::path& path);
/// A self-contained HTML page of the same tables.
std::string StressHtml(const std::vector<StressEntry>& entries);

}  // namespace talus::harness
