// The numeric flags that several talus-testbed subcommands share, each
// with its range (flag_range.h InRange), so `run`, `check` and `sweep`
// refuse a value the same way: "--jobs: 5000 is outside the range 0 to
// 1024".
#pragma once

#include "flag_range.h"
#include "talus/harness/scenario/scenario_limits.h"

namespace talus::testbed {

using flags::InRange;

/// --time-step: seconds in (0, 1], the scenario schema's bound on
/// "timeStep" (scenarios/schema.json), which ExpandStepping checks again.
inline const CLI::Validator kTimeStepRange = InRange(0.0, 1.0, /*lowerOpen=*/true);

/// --iterations: 0 (the engine's default) or the scenario schema's 1 to
/// 100000 for "iterations".
inline const CLI::Validator kIterationsRange = InRange(0, 100000);

/// --jobs: 0 (every core) to kMaxJobs threads.
inline const CLI::Validator kJobsRange = InRange(0, harness::kMaxJobs);

}  // namespace talus::testbed
