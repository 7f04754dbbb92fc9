// The sweep's noise floor (docs/testbed-sweeps.md, "Noise floor"): every
// sweep point is run as the unperturbed scenario plus K perturbed copies,
// whose dynamic bodies start moved by round-off (scenario/position_perturbation.h,
// PerturbDynamicPositions). A point then records how far its error moves
// under that perturbation (its error spread) and the median of its wall
// times, so that the comparison of fronts (cost_error_front.h) can tell a difference
// from the round-off lottery and from one noisy timing.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "talus/harness/run/runner.h"
#include "talus/harness/scenario/scenario.h"
#include "talus/result.h"

namespace talus::harness {

/// Perturbed copies per sweep point by default. Two copies give three runs
/// a point: the smallest count whose median wall time outvotes one noisy
/// timing, and two independent draws of the round-off lottery; each copy
/// costs one more whole sweep, so more would multiply an 18-minute sweep
/// further for a spread that only widens slowly with K.
inline constexpr int kDefaultPerturbCopies = 2;

/// Most copies accepted: a bound on a mistyped count (every copy is one
/// more whole sweep).
inline constexpr int kMaxPerturbCopies = 16;

/// Default perturbation, metres: the project's round-off scale (1e-9 m,
/// docs/testbed-sweeps.md).
inline constexpr double kDefaultSweepPerturbation = 1e-9;

/// The seed of copy 1; copy k (1-based) is seeded RepeatSeed(kSweepPerturbSeed,
/// k - 1), the same for every sweep point, so copy k of two points differs
/// only by their time step and iterations.
inline constexpr std::uint64_t kSweepPerturbSeed = 20261124;

/// Why `copies` is not a usable copy count (outside 0..kMaxPerturbCopies),
/// naming the option, or nothing.
std::optional<std::string> PerturbCopiesProblem(int copies);

/// Why `amount` is not a usable sweep perturbation (NaN, infinite, <= 0 or
/// above kMaxPositionPerturbation, position_perturbation.h), naming the
/// option.
std::optional<std::string> SweepPerturbationProblem(double amount);

/// Each run followed by its `copies` perturbed copies (copy k: every
/// dynamic body's initial position moved by PerturbDynamicPositions(amount,
/// RepeatSeed(kSweepPerturbSeed, k - 1))); the copies keep the run's id
/// with " perturbed copy k" appended. Each copy's truths that name a body's
/// start (free fall's y0, the projectile's x0, the bounce's drop height)
/// move with that body, so a copy is judged against the truth of its own
/// start. 0 copies returns `runs` unchanged.
Result<std::vector<Run>> WithPerturbedCopies(const std::vector<Run>& runs, int copies, double amount);

/// The spread of a point's error over its runs (RunErrorScalar of each):
/// max - min; a failed run counts as an infinite error; 0 when every run is
/// infinite (they agree), +infinity when only some are.
double ErrorSpread(const std::vector<double>& errors);

/// Folds RunAll's results over WithPerturbedCopies' runs back to one
/// result per (run, backend): `resultCounts` holds, per original run, how
/// many backends ran it (each copy ran on the same ones). Each kept result
/// is the unperturbed run's, with `perturbed` filled in (every run's error
/// and total wall time), its total wall time replaced by the median over
/// the run and its copies (RunCost) and its longest step by the longest of
/// all. An Error when the results do not match the counts (a copy ran on
/// other backends).
Result<std::vector<RunResult>> FoldPerturbedCopies(std::vector<RunResult> results,
                                                   const std::vector<int>& resultCounts, int copies,
                                                   double amount);

}  // namespace talus::harness
