// What one run records: a time series of samples, each the full state of
// every body plus whole-world measures, taken at the initial state (step 0)
// and then after every `stride`-th step, and always after the last step.
//
// Invariants: samples are in increasing step order; samples.front() is step
// 0 (before any Step()); samples.back() is the run's last step; each
// sample's time is exactly step * timeStep. Consumers (truth evaluators,
// the converged-reference comparison) must read each sample's own step and
// time and never assume a stride of 1: long runs are thinned.
#pragma once

#include <string>
#include <vector>

#include "talus/harness/backend/backend.h"

namespace talus::harness {

/// The state of the world after `step` steps.
struct Sample {
  int step = 0;                     ///< steps taken so far (0 = initial state)
  double time = 0.0;                ///< seconds: step * the run's time step
  std::vector<BodyReading> bodies;  ///< one per scenario body, in scenario order
  WorldMeasures measures;           ///< energies and momenta of the dynamic bodies
  int contactCount = 0;             ///< contact points the backend reported after this step
  double maxPenetration = 0.0;      ///< metres: the largest contact depth (0 when none overlap)
  /// The contacts themselves and the backend's step counters: only when the
  /// trajectory was recorded with detail (for replays), else empty.
  std::vector<ContactReading> contacts;
  std::vector<StepCounter> counters;
};

/// A run's record.
struct Trajectory {
  double timeStep = 0.0;        ///< seconds per step
  int stride = 1;               ///< steps between recorded samples (>= 1); the last step is always recorded
  std::vector<Sample> samples;  ///< see the invariants above
  /// Why recording stopped before the last step, e.g. "step 12: bullet:
  /// body \"ball\": non-finite position (nan, nan, nan)"; empty when every
  /// step ran. When set, the samples end at the last good step and the
  /// invariants above about the last step do not hold.
  std::string failure;
};

/// The stride that keeps a run of `steps` steps to at most `maxSamples`
/// samples (plus the initial one): ceil(steps / maxSamples), at least 1.
int SampleStride(int steps, int maxSamples);

/// Whether step `step` of a run of `steps` steps with `stride` is recorded.
bool IsSampled(int step, int steps, int stride);

/// At most `most` indices into `count` samples, spread evenly from the first
/// to the last (both kept when most >= 2; only the first when most is 1),
/// increasing, none repeated: which samples a plot series or a replay keeps.
std::vector<std::size_t> SpreadIndices(std::size_t count, std::size_t most);

}  // namespace talus::harness
