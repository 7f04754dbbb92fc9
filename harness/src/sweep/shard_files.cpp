// The "i/n" shard specification, the partition of runs and the shard
// file's JSON (shards.h). The partition is by run, round robin (run r goes
// to shard r mod n), so each shard gets every stepping of a sweep in turn
// and the shards' costs stay close; a run's backends stay together, so the
// runner's threading (runner.h: serial lanes per library) works within
// each shard unchanged.
#include <charconv>
#include <nlohmann/json.hpp>
#include <optional>
#include <type_traits>

#include "support/fnv1a.h"
#include "support/text_util.h"
#include "talus/harness/scenario/scenario_limits.h"
#include "talus/harness/sweep/shards.h"

namespace talus::harness {
namespace {

constexpr std::string_view kShardFormat = "talus-testbed-shard";
// Version 2 added the identity (build, settings, scenarios, digest);
// version 3 the payload digest. Older files cannot be checked (against
// each other, or for edits) and are refused.
constexpr int kShardVersion = 3;
// The key of the payload digest and its value's prefix (the algorithm).
constexpr const char* kDigestKey = "payloadDigest";
constexpr std::string_view kDigestPrefix = "fnv1a64:";

// The payload digest of a shard's JSON without its digest field: FNV-1a 64
// (support/fnv1a.h) of the compact dump of every other field, in file
// order. The dump is canonical (nlohmann's number and string forms), so
// re-indenting the file keeps its digest; changing any value does not.
std::string PayloadDigest(const nlohmann::ordered_json& payload) {
  Fnv1a64 hash;
  hash.AddBytes(payload.dump());
  return Concat({kDigestPrefix, hash.Hex()});
}

// The values of `in[key]`, an array of T; false when it is not one.
template <typename T>
bool ReadArray(const nlohmann::ordered_json& in, const char* key, std::vector<T>& out) {
  if (!in.contains(key) || !in[key].is_array()) return false;
  for (const auto& item : in[key]) {
    if constexpr (std::is_same_v<T, std::string>) {
      if (!item.is_string()) return false;
    } else if constexpr (std::is_integral_v<T>) {
      if (!item.is_number_integer()) return false;
    } else {
      if (!item.is_number()) return false;
    }
    out.push_back(item.get<T>());
  }
  return true;
}

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
  if (count.Value() < 1)
    return Error{Concat({"shard \"", text, "\": need at least 1 shard (i/n with n >= 1)"})};
  if (index.Value() < 0 || index.Value() >= count.Value()) {
    // "--shard 2/2" is a natural guess at the second of two: say how they
    // are numbered.
    const int n = count.Value();
    return Error{Concat({"shard \"", text, "\": shard index ", std::to_string(index.Value()),
                         " out of range for ", std::to_string(n), n == 1 ? " shard" : " shards",
                         " (shards are numbered 0 to ", std::to_string(n - 1), ")"})};
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
  out["version"] = kShardVersion;
  out["shard"] = shard.shard.index;
  out["count"] = shard.shard.count;
  out["build"] = shard.identity.build;
  out["timeSteps"] = shard.identity.timeSteps;
  out["iterations"] = shard.identity.iterations;
  out["scenarios"] = shard.identity.scenarios;
  out["runsDigest"] = shard.identity.runsDigest;
  out["perturbCopies"] = shard.identity.perturbCopies;
  out["perturbation"] = shard.identity.perturbation;
  out["runCount"] = shard.runCount;
  out["runIndices"] = shard.runIndices;
  if (!shard.resultCounts.empty()) out["resultCounts"] = shard.resultCounts;
  out["results"] = nlohmann::ordered_json::parse(ResultsToJson(shard.results));
  // The digest goes after the version, where a reader looks first; it
  // covers every other field.
  nlohmann::ordered_json file;
  for (auto it = out.begin(); it != out.end(); ++it) {
    file[it.key()] = it.value();
    if (it.key() == "version") file[kDigestKey] = PayloadDigest(out);
  }
  return file.dump(2) + "\n";
}

namespace {

// What makes `in` not a shard file of this version: its format, version,
// partition integers or run list missing; nullopt when none.
std::optional<std::string> ShardHeaderProblem(const nlohmann::ordered_json& in) {
  if (in.value("format", std::string()) != kShardFormat) {
    return Concat({"shard file: \"format\" is not \"", kShardFormat, "\""});
  }
  if (in.value("version", 0) != kShardVersion) {
    const bool older = in.contains("version") && in["version"].is_number_integer() &&
                       in["version"].get<long long>() >= 1 && in["version"].get<long long>() < kShardVersion;
    return Concat({"shard file: version ", in.contains("version") ? in["version"].dump() : "(none)",
                   ", expected ", std::to_string(kShardVersion),
                   older ? " (written by an older talus-testbed: its shard files carry no digest of their "
                           "contents, so an edit cannot be detected; re-run the shard with this build)"
                         : " (re-run the shard with this build)"});
  }
  for (const char* key : {"shard", "count", "runCount"}) {
    if (!in.contains(key) || !in[key].is_number_integer()) {
      return Concat({"shard file: missing integer \"", key, "\""});
    }
  }
  if (!in.contains("runIndices") || !in["runIndices"].is_array() || !in.contains("results")) {
    return "shard file: missing \"runIndices\" or \"results\"";
  }
  return std::nullopt;
}

// Why `in`'s contents do not match its payload digest, or nullopt when
// they do: a value edited by hand (a measured value, a verdict, a
// backend) or a file damaged after it was written.
std::optional<std::string> DigestProblem(const nlohmann::ordered_json& in) {
  if (!in.contains(kDigestKey) || !in[kDigestKey].is_string()) {
    return Concat({"shard file: missing string \"", kDigestKey,
                   "\" (the digest of its contents, which every version ", std::to_string(kShardVersion),
                   " shard file carries)"});
  }
  const std::string written = in[kDigestKey].get<std::string>();
  nlohmann::ordered_json payload = in;
  payload.erase(kDigestKey);
  const std::string computed = PayloadDigest(payload);
  if (written == computed) return std::nullopt;
  return Concat({"shard file: the digest does not match its contents (", kDigestKey, " ", written,
                 ", contents hash to ", computed,
                 "): it was edited or damaged after talus-testbed wrote it; re-run the shard"});
}

// The identity the merge compares (build, digest, noise floor, settings,
// scenarios).
Result<ShardIdentity> ReadShardIdentity(const nlohmann::ordered_json& in) {
  ShardIdentity identity;
  if (!in.contains("build") || !in["build"].is_string() || !in.contains("runsDigest") ||
      !in["runsDigest"].is_string()) {
    return Error{"shard file: missing string \"build\" or \"runsDigest\""};
  }
  identity.build = in["build"].get<std::string>();
  identity.runsDigest = in["runsDigest"].get<std::string>();
  // Shard files written before the noise floor ran no copies.
  if (in.contains("perturbCopies") || in.contains("perturbation")) {
    if (!in.contains("perturbCopies") || !in["perturbCopies"].is_number_integer() ||
        !in.contains("perturbation") || !in["perturbation"].is_number()) {
      return Error{"shard file: \"perturbCopies\" (integer) and \"perturbation\" (number) go together"};
    }
    identity.perturbCopies = in["perturbCopies"].get<int>();
    identity.perturbation = in["perturbation"].get<double>();
  }
  if (!ReadArray(in, "timeSteps", identity.timeSteps) || !ReadArray(in, "iterations", identity.iterations) ||
      !ReadArray(in, "scenarios", identity.scenarios)) {
    return Error{
        "shard file: \"timeSteps\", \"iterations\" and \"scenarios\" must be arrays of numbers, "
        "integers and strings"};
  }
  return identity;
}

// Bounded before anything is sized by them: a partition has at most
// kMaxRuns runs and shards (a forged count must not make the merge
// allocate gigabytes).
std::optional<std::string> PartitionBoundsProblem(const nlohmann::ordered_json& in) {
  const auto inRange = [&](const char* key, long long low, long long high) {
    const long long value = in[key].get<long long>();
    return value >= low && value <= high;
  };
  const auto maxRuns = static_cast<long long>(kMaxRuns);
  if (!inRange("runCount", 0, maxRuns) || !inRange("count", 1, maxRuns) ||
      !inRange("shard", 0, in["count"].get<long long>() - 1)) {
    return Concat({"shard file: need 0 <= shard < count and count, runCount <= ", std::to_string(kMaxRuns),
                   "; got shard ", in["shard"].dump(), ", count ", in["count"].dump(), ", runCount ",
                   in["runCount"].dump()});
  }
  return std::nullopt;
}

// The shard's place in the partition and its results, into `shard`.
std::optional<std::string> ReadRunsAndResults(const nlohmann::ordered_json& in, ShardFile& shard) {
  shard.shard = {in["shard"].get<int>(), in["count"].get<int>()};
  shard.runCount = in["runCount"].get<int>();
  for (const auto& index : in["runIndices"]) {
    if (!index.is_number_integer()) return "shard file: runIndices must be integers";
    shard.runIndices.push_back(index.get<int>());
  }
  if (in.contains("resultCounts")) {
    if (!in["resultCounts"].is_array()) return "shard file: resultCounts must be an array";
    for (const auto& count : in["resultCounts"]) {
      if (!count.is_number_integer()) return "shard file: resultCounts must be integers";
      shard.resultCounts.push_back(count.get<int>());
    }
  }
  auto results = ResultsFromJson(in["results"].dump());
  if (!results) return Concat({"shard file: ", results.GetError().message});
  shard.results = std::move(results).Value();
  return std::nullopt;
}

}  // namespace

Result<ShardFile> ShardFromJson(std::string_view text) {
  nlohmann::ordered_json in = nlohmann::ordered_json::parse(text, nullptr, false);
  if (in.is_discarded() || !in.is_object()) return Error{"shard file: not JSON"};
  if (auto problem = ShardHeaderProblem(in)) return Error{*problem};
  auto identity = ReadShardIdentity(in);
  if (!identity) return identity.GetError();
  if (auto problem = PartitionBoundsProblem(in)) return Error{*problem};
  if (auto problem = DigestProblem(in)) return Error{*problem};
  ShardFile shard;
  shard.identity = std::move(identity).Value();
  if (auto problem = ReadRunsAndResults(in, shard)) return Error{*problem};
  return shard;
}

}  // namespace talus::harness
