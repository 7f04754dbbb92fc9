// Run time against error: the analysis of a stepping sweep and the sharding
// of long job lists, one header for the code that uses all of it (the
// testbed's sweep and merge commands, the report). Each part has its own
// header:
//   cost_error_front.h  one run's (cost, error) point, Pareto fronts, the
//                       comparison at one budget and at equal cost;
//   family_verdict.h    every engine family against every other;
//   sweep_analysis.h    results grouped into curves per scenario instance,
//                       fronts and verdicts per group, the family tallies;
//   sweep_text.h        the analysis as JSON, Markdown and report.html;
//   shards.h            the "i/n" partition, shard files and their merge.
// Definitions in docs/testbed-sweeps.md and docs/sharding.md.
#pragma once

#include "talus/harness/sweep/cost_error_front.h"
#include "talus/harness/sweep/family_verdict.h"
#include "talus/harness/sweep/shards.h"
#include "talus/harness/sweep/sweep_analysis.h"
#include "talus/harness/sweep/sweep_text.h"
