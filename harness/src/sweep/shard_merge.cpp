// MergeShards (shards.h): every shard of one partition checked against the
// first, then their results put back in the unsharded run order.
#include <algorithm>
#include <charconv>
#include <optional>

#include "support/text_util.h"
#include "talus/harness/sweep/shards.h"

namespace talus::harness {
namespace {

std::string ListText(const std::vector<double>& values) {
  std::string text;
  for (double v : values) {
    char number[32];
    // Shortest round-trip form: 0.05, not 0.050000000000000003.
    const auto end = std::to_chars(number, number + sizeof number, v).ptr;
    text.append(text.empty() ? "" : ",").append(number, end);
  }
  return text;
}

std::string ListText(const std::vector<int>& values) {
  std::string text;
  for (int v : values) text.append(text.empty() ? "" : ",").append(std::to_string(v));
  return text;
}

std::string ListText(const std::vector<std::string>& values) {
  std::string text;
  for (const std::string& v : values) text.append(text.empty() ? "" : ",").append(v);
  return text;
}

// Why `shard` cannot be merged with `first`, or "" when they are of one
// partition; `name` and `firstName` label them ("shard 1/4").
std::string PartitionMismatch(const ShardFile& shard, const std::string& name, const ShardFile& first,
                              const std::string& firstName) {
  const auto differ = [&](const std::string& what, const std::string& mine, const std::string& theirs) {
    return Concat({name, " has ", what, " ", Quoted(mine), " but ", firstName, " has ", Quoted(theirs)});
  };
  const ShardIdentity& a = shard.identity;
  const ShardIdentity& b = first.identity;
  if (shard.shard.count != first.shard.count) {
    return Concat({name, " is one of ", std::to_string(shard.shard.count), " shards but ", firstName,
                   " one of ", std::to_string(first.shard.count)});
  }
  if (a.build != b.build) return differ("build", a.build, b.build) + " (merge shards of one build)";
  if (a.timeSteps != b.timeSteps) return differ("time steps", ListText(a.timeSteps), ListText(b.timeSteps));
  if (a.iterations != b.iterations) {
    return differ("iterations", ListText(a.iterations), ListText(b.iterations));
  }
  if (shard.results.backends != first.results.backends) {
    return differ("backends", ListText(shard.results.backends), ListText(first.results.backends));
  }
  if (shard.results.deterministic != first.results.deterministic) {
    return differ("--deterministic", shard.results.deterministic ? "on" : "off",
                  first.results.deterministic ? "on" : "off");
  }
  if (a.perturbCopies != b.perturbCopies || a.perturbation != b.perturbation) {
    return differ(
        "perturbed copies (count, m)",
        Concat({std::to_string(a.perturbCopies), ", ", ListText(std::vector<double>{a.perturbation})}),
        Concat({std::to_string(b.perturbCopies), ", ", ListText(std::vector<double>{b.perturbation})}));
  }
  for (const std::string& scenario : a.scenarios) {
    if (std::find(b.scenarios.begin(), b.scenarios.end(), scenario) == b.scenarios.end()) {
      return Concat({name, " ran scenario ", Quoted(scenario), ", which ", firstName, " did not"});
    }
  }
  for (const std::string& scenario : b.scenarios) {
    if (std::find(a.scenarios.begin(), a.scenarios.end(), scenario) == a.scenarios.end()) {
      return Concat({firstName, " ran scenario ", Quoted(scenario), ", which ", name, " did not"});
    }
  }
  if (a.runsDigest != b.runsDigest || shard.runCount != first.runCount) {
    return Concat(
        {name, " and ", firstName, " ran the same scenario names with different contents (runs digest ",
         a.runsDigest, " and ", b.runsDigest, ", ", std::to_string(shard.runCount), " and ",
         std::to_string(first.runCount), " runs): the scenario files differ between their machines"});
  }
  return {};
}

}  // namespace

Result<ResultsFile> MergeShards(const std::vector<ShardFile>& shards) {
  if (shards.empty()) return Error{"merge: no shards"};
  const ShardFile& first = shards.front();
  const std::size_t backends = first.results.backends.size();
  if (backends == 0) return Error{"merge: shard has no backends"};
  // Each run's results, in the runner's order; a run of no shard stays null.
  std::vector<std::optional<std::vector<const RunResult*>>> byRun(static_cast<std::size_t>(first.runCount));
  std::vector<int> seenShards(static_cast<std::size_t>(first.shard.count), 0);
  for (const ShardFile& shard : shards) {
    const std::string name =
        Concat({"shard ", std::to_string(shard.shard.index), "/", std::to_string(shard.shard.count)});
    const std::string firstName =
        Concat({"shard ", std::to_string(first.shard.index), "/", std::to_string(first.shard.count)});
    if (const std::string mismatch = PartitionMismatch(shard, name, first, firstName); !mismatch.empty()) {
      return Error{TidyMessage(Concat({"merge: ", mismatch}))};
    }
    if (shard.shard.index < 0 || shard.shard.index >= shard.shard.count) {
      return Error{Concat({"merge: ", name, ": index out of range"})};
    }
    if (seenShards[shard.shard.index]++ > 0) return Error{Concat({"merge: ", name, " given twice"})};
    std::vector<int> counts = shard.resultCounts;
    if (counts.empty()) counts.assign(shard.runIndices.size(), static_cast<int>(backends));
    std::size_t total = 0;
    bool countsFit = counts.size() == shard.runIndices.size();
    for (int count : counts) {
      countsFit = countsFit && count >= 0 && static_cast<std::size_t>(count) <= backends;
      total += static_cast<std::size_t>(std::max(count, 0));
    }
    if (shard.runIndices != ShardRuns(shard.runCount, shard.shard) || !countsFit ||
        shard.results.results.size() != total) {
      return Error{Concat({"merge: ", name, ": its runs are not the partition's"})};
    }
    std::size_t next = 0;
    for (std::size_t k = 0; k < shard.runIndices.size(); ++k) {
      auto& slot = byRun[static_cast<std::size_t>(shard.runIndices[k])].emplace();
      for (int b = 0; b < counts[k]; ++b) slot.push_back(&shard.results.results[next++]);
    }
  }
  for (int i = 0; i < first.shard.count; ++i) {
    if (seenShards[i] == 0) {
      return Error{
          Concat({"merge: shard ", std::to_string(i), "/", std::to_string(first.shard.count), " missing"})};
    }
  }
  ResultsFile merged;
  merged.backends = first.results.backends;
  merged.deterministic = first.results.deterministic;
  for (const auto& run : byRun) {
    for (const RunResult* result : *run) merged.results.push_back(*result);
  }
  return merged;
}
}  // namespace talus::harness
