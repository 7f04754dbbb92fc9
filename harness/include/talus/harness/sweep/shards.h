// Sharding long job lists: a job is one (run, backend); shard i of n takes
// every job of the runs whose index r (in the expanded run list) has
// r mod n == i, so the n shards cover every job exactly once and
// MergeShards puts them back in the unsharded order (docs/sharding.md).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "talus/harness/run/results_file.h"
#include "talus/harness/scenario/scenario.h"
#include "talus/result.h"

namespace talus::harness {

/// A shard specification "i/n" (0 <= i < n); an Error names the text.
struct Shard {
  int index = 0;
  int count = 1;
};
Result<Shard> ParseShard(std::string_view text);

/// The run indices of shard `shard` among `runCount` runs (r mod n == i).
std::vector<int> ShardRuns(int runCount, Shard shard);

/// What every shard of one partition must share besides its backends and
/// deterministic mode (which its results file holds): the build that ran
/// it, the sweep's stepping settings and the runs themselves. The merge
/// compares each part and names the first that differs.
struct ShardIdentity {
  std::string build;              ///< BuildId() of the program that ran the shard
  std::vector<double> timeSteps;  ///< the sweep's time steps, s, as given
  std::vector<int> iterations;    ///< the sweep's iteration counts, as given
  /// The scenarios of the unsharded run list, first appearance order, each
  /// once (names as in the files).
  std::vector<std::string> scenarios;
  /// 16 hex digits: FNV-1a 64 over every run of the unsharded list (its id,
  /// stepping and its scenario as ScenarioToJson writes it), so two
  /// partitions agree only when every scenario file read the same.
  std::string runsDigest;
  /// The noise floor's settings (perturbed_copies.h): copies per point and
  /// metres (0 without copies); shard files without them are of 0 copies.
  int perturbCopies = 0;
  double perturbation = 0.0;
};

/// The identity of a sweep over `runs` (the unsharded, expanded list) with
/// the given settings, run by this build.
ShardIdentity MakeShardIdentity(const std::vector<Run>& runs, const std::vector<double>& timeSteps,
                                const std::vector<int>& iterations);

/// A shard's results: the results file of its runs plus where they go.
struct ShardFile {
  Shard shard;
  ShardIdentity identity;
  int runCount = 0;             ///< runs in the unsharded list
  std::vector<int> runIndices;  ///< this shard's runs, increasing
  ResultsFile results;          ///< the runs' results, run-major (the runner's order)
  /// Results per entry of runIndices: the backends that ran it (fewer than
  /// results.backends when its scenario lists backends, possibly 0). Empty
  /// means every run has one result per backend.
  std::vector<int> resultCounts;
};
/// The shard file's JSON (version 3), with the digest of its payload
/// ("payloadDigest": FNV-1a 64 of every other field's canonical dump,
/// docs/sharding.md) / read back: an Error when the digest does not match
/// the contents (an edited measured value, verdict, backend, step count,
/// time step or trajectory point), when it is missing, or for a file of an
/// older version (which carries none).
std::string ShardToJson(const ShardFile& shard);
Result<ShardFile> ShardFromJson(std::string_view text);

/// The unsharded results from every shard of one partition, each run
/// exactly once; else an Error naming the shard and what is wrong: a shard
/// missing or given twice, or shards from different partitions (another
/// shard count, build, time steps, iterations, backends, deterministic
/// mode, perturbed copies, scenario set or scenario contents).
Result<ResultsFile> MergeShards(const std::vector<ShardFile>& shards);

}  // namespace talus::harness
