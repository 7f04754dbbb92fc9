// Perturbed repeats of a reference benchmark scene: the round-off probe of
// issue 12 ("the pyramid verdict must not be a round-off lottery").
//
// A scene's verdict (pyramid: drift <= 5 mm; hull_pile: nothing escapes)
// is only worth judging code by if it does not hang on the last bits of the
// initial state. The perturbation itself (PerturbDynamicPositions,
// RepeatSeed) is scenario/position_perturbation.h's, shared with the
// sweep's noise floor; repeat r of a series is seeded with RepeatSeed(seed,
// r). SummarizeRepeats reduces a series of runs to the spread of the
// scene's figure and says whether the verdict held the same way in every
// repeat (docs/bench-scenes.md, "Perturbed repeats").
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "talus/harness/scenario/position_perturbation.h"
#include "talus/harness/scenario/scenario.h"
#include "talus/harness/scenes/bench_run.h"
#include "talus/result.h"

namespace talus::harness {

/// Largest number of repeats of one (scene, engine) pair: a bound on a
/// mistyped count (pyramid 15 takes about 15 s a run on one core).
inline constexpr int kMaxBenchRepeats = 1000;

/// The pyramid's verdict (issue 12's goal): it holds when drift_m <= this,
/// metres. Stricter than the 5 cm "stands" line of docs/bench-scenes.md.
inline constexpr double kPyramidDriftGoal = 0.005;

/// Why `repeats` is not a usable repeat count (outside 1..kMaxBenchRepeats),
/// or nothing when it is.
std::optional<std::string> BenchRepeatsProblem(int repeats);

/// The scene's verdict for one run: pyramid, drift_m <= kPyramidDriftGoal
/// (a NaN drift fails); hull_pile, no body escaped. Nothing for a skipped
/// run or one without its figure.
std::optional<bool> BenchVerdict(const BenchReport& report);

/// The figure a scene's verdict reads: drift_m for the pyramid,
/// max_penetration_m for the hull pile (whose verdict, escaped == 0, is a
/// count; the penetration shows how close the pile came to it).
std::optional<double> BenchVerdictFigure(const BenchReport& report);

/// The spread of a series of repeats of one (scene, parameter, engine).
struct BenchRepeatSummary {
  int runs = 0;             ///< repeats that were made (not skipped)
  double min = 0.0;         ///< smallest BenchVerdictFigure (NaN if any is NaN)
  double median = 0.0;      ///< median BenchVerdictFigure
  double max = 0.0;         ///< largest BenchVerdictFigure (NaN if any is NaN)
  int verdictsHeld = 0;     ///< runs whose BenchVerdict held
  bool sameVerdict = true;  ///< all held or none did
  /// The cost over the repeats: each run's total wall time (BenchReport::
  /// totalMs), milliseconds. The median across repeated runs is the one
  /// median of a time the benchmark takes (never one across steps).
  double totalMsMin = 0.0;
  double totalMsMedian = 0.0;
  double totalMsMax = 0.0;
};

/// Reduces the repeats of one series; skipped runs are left out. An empty
/// series (or one where every run was skipped) is an Error.
Result<BenchRepeatSummary> SummarizeRepeats(const std::vector<BenchReport>& repeats);

/// One readable line: "<scene> <P>=<n> <engine>: <figure> over N repeats
/// (+-amount m, seed S): min .. median .. max ..; verdict <rule> held in K of
/// N: same|DIFFERS; total ms min .. median .. max ..".
std::string FormatRepeatSummary(const BenchReport& first, const BenchRepeatSummary& summary);

}  // namespace talus::harness
