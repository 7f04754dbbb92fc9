// Sharding of a job list (sweep.h): the "i/n" specification, the
// deterministic partition of runs, a shard's file and the merge that
// rebuilds the unsharded results.
//
// The partition is by run, round robin (run r goes to shard r mod n), so
// each shard gets every stepping of a sweep in turn and the shards' costs
// stay close; a run's backends stay together, so the runner's threading
// (runner.h: serial lanes per library) works within each shard unchanged.
#include <algorithm>
#include <charconv>
#include <nlohmann/json.hpp>

#include "talus/harness/sweep.h"
#include "text_util.h"

namespace talus::harness {
namespace {

constexpr std::string_view kShardFormat = "talus-testbed-shard";

Result<int> ParseInt(std::string_view text, std::string_view whole) {
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || text.empty()) {
    return Error{Concat({"shard \"", whole, "\": expected i/n with integers 0 <= i < n"})};
  }
  return value;
}

}  // namespace

Result<Shard> ParseShard(std::string_view text) {
  const auto slash = text.find('/');
  if (slash == std::string_view::npos) return Error{Concat({"shard \"", text, "\": expected i/n"})};
  auto index = ParseInt(text.substr(0, slash), text);
  if (!index) return index.GetError();
  auto count = ParseInt(text.substr(slash + 1), text);
  if (!count) return count.GetError();
  if (count.Value() < 1 || index.Value() < 0 || index.Value() >= count.Value()) {
    return Error{Concat({"shard \"", text, "\": need 0 <= i < n"})};
  }
  return Shard{index.Value(), count.Value()};
}

std::vector<int> ShardRuns(int runCount, Shard shard) {
  std::vector<int> runs;
  for (int r = shard.index; r < runCount; r += shard.count) runs.push_back(r);
  return runs;
}

std::string ShardToJson(const ShardFile& shard) {
  nlohmann::ordered_json out;
  out["format"] = kShardFormat;
  out["version"] = 1;
  out["shard"] = shard.shard.index;
  out["count"] = shard.shard.count;
  out["runCount"] = shard.runCount;
  out["runIndices"] = shard.runIndices;
  out["results"] = nlohmann::ordered_json::parse(ResultsToJson(shard.results));
  return out.dump(2) + "\n";
}

Result<ShardFile> ShardFromJson(std::string_view text) {
  nlohmann::ordered_json in = nlohmann::ordered_json::parse(text, nullptr, false);
  if (in.is_discarded() || !in.is_object()) return Error{"shard file: not JSON"};
  if (in.value("format", std::string()) != kShardFormat) {
    return Error{Concat({"shard file: \"format\" is not \"", kShardFormat, "\""})};
  }
  for (const char* key : {"shard", "count", "runCount"}) {
    if (!in.contains(key) || !in[key].is_number_integer()) {
      return Error{Concat({"shard file: missing integer \"", key, "\""})};
    }
  }
  if (!in.contains("runIndices") || !in["runIndices"].is_array() || !in.contains("results")) {
    return Error{"shard file: missing \"runIndices\" or \"results\""};
  }
  ShardFile shard;
  shard.shard = {in["shard"].get<int>(), in["count"].get<int>()};
  shard.runCount = in["runCount"].get<int>();
  for (const auto& index : in["runIndices"]) {
    if (!index.is_number_integer()) return Error{"shard file: runIndices must be integers"};
    shard.runIndices.push_back(index.get<int>());
  }
  auto results = ResultsFromJson(in["results"].dump());
  if (!results) return Error{Concat({"shard file: ", results.GetError().message})};
  shard.results = std::move(results).Value();
  return shard;
}

Result<ResultsFile> MergeShards(const std::vector<ShardFile>& shards) {
  if (shards.empty()) return Error{"merge: no shards"};
  const ShardFile& first = shards.front();
  const std::size_t backends = first.results.backends.size();
  if (backends == 0) return Error{"merge: shard has no backends"};
  std::vector<const RunResult*> byRun(static_cast<std::size_t>(first.runCount) * backends, nullptr);
  std::vector<int> seenShards(static_cast<std::size_t>(first.shard.count), 0);
  for (const ShardFile& shard : shards) {
    const std::string name =
        Concat({"shard ", std::to_string(shard.shard.index), "/", std::to_string(shard.shard.count)});
    if (shard.shard.count != first.shard.count || shard.runCount != first.runCount ||
        shard.results.backends != first.results.backends ||
        shard.results.deterministic != first.results.deterministic) {
      return Error{Concat({"merge: ", name,
                           " is not from the same partition (shard count, run count, backends or "
                           "deterministic mode differ)"})};
    }
    if (shard.shard.index < 0 || shard.shard.index >= shard.shard.count) {
      return Error{Concat({"merge: ", name, ": index out of range"})};
    }
    if (seenShards[shard.shard.index]++ > 0) return Error{Concat({"merge: ", name, " given twice"})};
    if (shard.runIndices != ShardRuns(shard.runCount, shard.shard) ||
        shard.results.results.size() != shard.runIndices.size() * backends) {
      return Error{Concat({"merge: ", name, ": its runs are not the partition's"})};
    }
    for (std::size_t k = 0; k < shard.runIndices.size(); ++k) {
      for (std::size_t b = 0; b < backends; ++b) {
        byRun[static_cast<std::size_t>(shard.runIndices[k]) * backends + b] =
            &shard.results.results[k * backends + b];
      }
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
  for (const RunResult* result : byRun) merged.results.push_back(*result);
  return merged;
}

}  // namespace talus::harness
