// The invariants of the harness fuzz targets (scenario loader, shard
// merge), apart from libFuzzer so that tests/fuzz/ replays their corpora in
// the ordinary build. Each returns "" when every check passes, else what
// failed.
#pragma once

#include <string>
#include <string_view>

#include "talus/harness/scenario/scenario.h"

namespace talus::fuzz {

/// Where two scenario models differ ("" when equal): every field, exactly,
/// except the file name and the unit vectors the loader normalises
/// (orientations, sliding directions, hull_rest normals), which may differ
/// by 4 ulps per component (renormalising a unit vector can move its last
/// bits).
std::string ScenarioDifference(const harness::Scenario& a, const harness::Scenario& b);

/// Parses `text` as a scenario file. An error must name the file and be one
/// printable line of at most 2 KiB. A success must round-trip: each run's
/// scenario, written with ScenarioToJson and parsed again, gives one run
/// with the same model and stepping, and writing that again gives the same
/// text (up to the normalised unit vectors).
std::string CheckScenarioRoundTrip(std::string_view text);

/// Reads `text` as shard files separated by lines "----": every one that
/// parses must write back (ShardToJson) to text that parses to the same
/// file; the merge of the parsed shards must fail with a "merge: " message
/// or succeed with every shard's results exactly once, and give the same
/// results file when the shards come in reverse order.
std::string CheckShardMerge(std::string_view text);

}  // namespace talus::fuzz
