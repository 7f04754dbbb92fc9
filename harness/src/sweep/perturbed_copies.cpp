// The sweep's perturbed copies and their fold (see
// talus/harness/sweep/perturbed_copies.h).
#include "talus/harness/sweep/perturbed_copies.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "support/numbers.h"
#include "support/text_util.h"
#include "talus/harness/scenario/position_perturbation.h"
#include "talus/harness/support/number_text.h"
#include "talus/harness/sweep/cost_error_front.h"
#include "talus/harness/truth/truth_check.h"

namespace talus::harness {
namespace {

// The truths of `moved` (a copy of `run` with its bodies moved) made those
// of its own start: a truth that names where a body starts (free fall's y0,
// the projectile's x0, the bounce's drop height above the floor it infers
// from the start, a state_at position) moves with that body, so the copy is
// judged on how it moved from where it began, not on the offset the copy
// injected (1e-9 m against free fall's 1e-9 m tolerance would be an error
// of 0.7).
void MoveTruthsWithTheirBodies(const Run& run, Run& moved) {
  const Vec3 up = UpAxis(run);
  for (Truth& truth : moved.scenario.truths) {
    if (truth.body < 0) continue;
    const auto body = static_cast<std::size_t>(truth.body);
    const Vec3 offset = moved.scenario.bodies[body].position - run.scenario.bodies[body].position;
    if (auto* fall = std::get_if<FreeFallTruth>(&truth.kind)) fall->y0 += offset.dot(up);
    if (auto* projectile = std::get_if<ProjectileTruth>(&truth.kind)) projectile->x0 += offset;
    if (auto* bounce = std::get_if<BounceHeightsTruth>(&truth.kind)) bounce->h += offset.dot(up);
    if (auto* state = std::get_if<StateAtTruth>(&truth.kind);
        state && state->quantity == StateQuantity::Position) {
      state->value += offset;
    }
  }
}

}  // namespace

std::optional<std::string> PerturbCopiesProblem(int copies) {
  if (copies < 0 || copies > kMaxPerturbCopies) {
    return Concat({"--perturb-copies ", std::to_string(copies), ": must be an integer in [0, ",
                   std::to_string(kMaxPerturbCopies), "] (each copy is one more whole sweep)"});
  }
  return std::nullopt;
}

std::optional<std::string> SweepPerturbationProblem(double amount) {
  // Written so that NaN fails the test too; 0 would make copies that are
  // the unperturbed run again, a spread of 0 that proves nothing.
  if (!(amount > 0.0 && amount <= kMaxPositionPerturbation)) {
    return Concat({"--perturb ", std::isnan(amount) ? std::string("NaN") : FormatNumber(amount),
                   ": must be a number of metres in (0, ", FormatNumber(kMaxPositionPerturbation), "]"});
  }
  return std::nullopt;
}

Result<std::vector<Run>> WithPerturbedCopies(const std::vector<Run>& runs, int copies, double amount) {
  if (auto problem = PerturbCopiesProblem(copies)) return Error{*problem};
  if (copies == 0) return runs;
  if (auto problem = SweepPerturbationProblem(amount)) return Error{*problem};
  std::vector<Run> all;
  all.reserve(runs.size() * static_cast<std::size_t>(copies + 1));
  for (const Run& run : runs) {
    all.push_back(run);
    for (int k = 1; k <= copies; ++k) {
      auto scene = PerturbDynamicPositions(run.scenario, amount, RepeatSeed(kSweepPerturbSeed, k - 1));
      if (!scene) return scene.GetError();
      Run copy = run;
      copy.scenario = std::move(scene).Value();
      MoveTruthsWithTheirBodies(run, copy);
      copy.id = Concat({run.id, " perturbed copy ", std::to_string(k)});
      all.push_back(std::move(copy));
    }
  }
  return all;
}

double ErrorSpread(const std::vector<double>& errors) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  int infinite = 0;
  double low = kInfinity;
  double high = -kInfinity;
  for (double error : errors) {
    if (!std::isfinite(error)) {
      ++infinite;  // a failed run (NaN) is an error never measured
      continue;
    }
    low = std::min(low, error);
    high = std::max(high, error);
  }
  if (infinite == static_cast<int>(errors.size())) return 0.0;
  if (infinite > 0) return kInfinity;
  return high - low;
}

Result<std::vector<RunResult>> FoldPerturbedCopies(std::vector<RunResult> results,
                                                   const std::vector<int>& resultCounts, int copies,
                                                   double amount) {
  if (auto problem = PerturbCopiesProblem(copies)) return Error{*problem};
  if (copies == 0) return results;
  std::vector<RunResult> folded;
  std::size_t next = 0;
  const auto runs = static_cast<std::size_t>(copies + 1);
  for (int count : resultCounts) {
    const auto backends = static_cast<std::size_t>(std::max(count, 0));
    if (next + runs * backends > results.size()) {
      return Error{"perturbed copies: fewer results than the runs and their copies"};
    }
    for (std::size_t b = 0; b < backends; ++b) {
      RunResult kept = std::move(results[next + b]);
      std::vector<double> errors;
      std::vector<double> totals;
      PerturbedRuns& perturbed = kept.perturbed;
      perturbed.copies = copies;
      perturbed.amount = amount;
      for (std::size_t c = 0; c < runs; ++c) {
        const RunResult& run = c == 0 ? kept : results[next + c * backends + b];
        if (run.backend != kept.backend) {
          return Error{Concat({"perturbed copies: ", kept.runId, ": copy ", std::to_string(c), " ran on ",
                               run.backend, ", not ", kept.backend})};
        }
        const double error = RunErrorScalar(run);
        errors.push_back(error);
        // A failed or unmeasured run is an error never measured: infinite.
        perturbed.errors.push_back(std::isnan(error) ? std::numeric_limits<double>::infinity() : error);
        totals.push_back(run.wallSeconds);
        perturbed.runSeconds.push_back(run.wallSeconds);
        // The longest step seen in any of them, NaN (unknown) kept.
        if (!(run.wallSecondsLongestStep <= kept.wallSecondsLongestStep))
          kept.wallSecondsLongestStep = run.wallSecondsLongestStep;
      }
      perturbed.errorSpread = ErrorSpread(errors);
      // A median across repeated runs (never across one run's steps): one
      // noisy timing among three does not move the cost.
      kept.wallSeconds = Median(totals);
      folded.push_back(std::move(kept));
    }
    next += runs * backends;
  }
  if (next != results.size()) return Error{"perturbed copies: more results than the runs and their copies"};
  return folded;
}

}  // namespace talus::harness
