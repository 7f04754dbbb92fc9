// The harness fuzz targets' invariants (see harness_checks.h).
#include "harness_checks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "talus/harness/run/results_file.h"
#include "talus/harness/scenario/scenario_loader.h"
#include "talus/harness/scenario/scenario_writer.h"
#include "talus/harness/sweep/sweep.h"

namespace talus::fuzz {
namespace {

using harness::BodySpec;
using harness::Scenario;

// Longest loader message accepted: TidyMessage cuts quoted spans to 64
// bytes, so only the file name, a JSON pointer and fixed text remain.
constexpr std::size_t kMaxLoaderMessage = 2048;

// Runs per fuzzed file whose round trip is checked: a sweep may expand to
// thousands, and the first few cover every sweep's first values.
constexpr std::size_t kMaxRunsChecked = 8;

// A unit vector renormalised by the loader: |x| <= 1, so 4 ulps of 1.
constexpr double kRenormalised = 4.0 * std::numeric_limits<double>::epsilon();

bool Near(const Vec3& a, const Vec3& b) { return (a - b).cwiseAbs().maxCoeff() <= kRenormalised; }

bool Near(const Quat& a, const Quat& b) {
  return Near(a.vec(), b.vec()) && std::abs(a.w() - b.w()) <= kRenormalised;
}

std::string BodyDifference(const BodySpec& a, const BodySpec& b) {
  const std::string at = "body \"" + a.name + "\": ";
  if (a.name != b.name) return at + "name";
  if (!(a.shape == b.shape)) return at + "shape";
  if (a.motion != b.motion) return at + "motion";
  if (a.position != b.position) return at + "position";
  if (!Near(a.orientation, b.orientation)) return at + "orientation";
  if (a.linearVelocity != b.linearVelocity) return at + "linearVelocity";
  if (a.angularVelocity != b.angularVelocity) return at + "angularVelocity";
  if (a.density != b.density || a.mass != b.mass) return at + "mass or density";
  if (a.friction != b.friction || a.restitution != b.restitution) return at + "friction or restitution";
  return {};
}

// The truth kinds whose unit vectors the loader normalises compare with
// Near; every other kind exactly (the structs' own operator==).
bool SameKind(const harness::TruthKind& a, const harness::TruthKind& b) {
  if (a.index() != b.index()) return false;
  if (const auto* slide = std::get_if<harness::SlidingStopTruth>(&a)) {
    harness::SlidingStopTruth other = std::get<harness::SlidingStopTruth>(b);
    if (!Near(slide->direction, other.direction)) return false;
    other.direction = slide->direction;
    return *slide == other;
  }
  if (const auto* rest = std::get_if<harness::HullRestTruth>(&a)) {
    harness::HullRestTruth other = std::get<harness::HullRestTruth>(b);
    if (!Near(rest->faceNormal, other.faceNormal)) return false;
    other.faceNormal = rest->faceNormal;
    return *rest == other;
  }
  return a == b;
}

bool SamePublished(const std::optional<harness::PublishedFigure>& a,
                   const std::optional<harness::PublishedFigure>& b) {
  if (a.has_value() != b.has_value()) return false;
  if (!a) return true;
  const bool upper = (std::isnan(a->upper) && std::isnan(b->upper)) || a->upper == b->upper;
  return a->value == b->value && upper && a->source == b->source;
}

bool Printable(std::string_view text) {
  return std::all_of(text.begin(), text.end(), [](char c) {
    const auto byte = static_cast<unsigned char>(c);
    return byte >= 0x20 || byte == '\t';
  });
}

}  // namespace

std::string ScenarioDifference(const Scenario& a, const Scenario& b) {
  if (a.name != b.name) return "name";
  if (a.description != b.description) return "description";
  if (!(a.world == b.world)) return "world settings";
  if (a.bodies.size() != b.bodies.size()) return "body count";
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    if (std::string body = BodyDifference(a.bodies[i], b.bodies[i]); !body.empty()) return body;
  }
  if (a.backends != b.backends) return "backends";
  if (a.measure != b.measure) return "measure";
  if (a.loads != b.loads) return "loads";
  if (a.impulses != b.impulses) return "impulses";
  if (a.truths.size() != b.truths.size()) return "truth count";
  for (std::size_t i = 0; i < a.truths.size(); ++i) {
    const harness::Truth& x = a.truths[i];
    const harness::Truth& y = b.truths[i];
    const std::string at = "truth " + std::to_string(i) + ": ";
    if (!SameKind(x.kind, y.kind)) return at + "kind or its fields";
    if (x.body != y.body) return at + "body";
    if (!(x.tolerance == y.tolerance) || x.toleranceReason != y.toleranceReason) return at + "tolerance";
    if (x.gate != y.gate || x.ungated != y.ungated) return at + "gate";
    if (!SamePublished(x.published, y.published)) return at + "published";
  }
  return {};
}

std::string CheckScenarioRoundTrip(std::string_view text) {
  auto runs = harness::ParseScenarioText(text, "fuzz.json");
  if (!runs) {
    const std::string& message = runs.GetError().message;
    if (!message.starts_with("fuzz.json")) return "error does not name the file: " + message.substr(0, 80);
    if (message.size() > kMaxLoaderMessage) return "error of " + std::to_string(message.size()) + " bytes";
    if (message.find('\n') != std::string::npos || !Printable(message)) {
      return "error is not one printable line: " + message.substr(0, 80);
    }
    return {};
  }
  if (runs.Value().empty()) return "a file loaded into no runs";
  const std::size_t count = std::min(runs.Value().size(), kMaxRunsChecked);
  for (std::size_t r = 0; r < count; ++r) {
    const harness::Run& run = runs.Value()[r];
    const std::string saved = harness::ScenarioToJson(run.scenario);
    auto again = harness::ParseScenarioText(saved, "fuzz.json");
    if (!again) return "run " + run.id + ": the saved scenario does not load: " + again.GetError().message;
    if (again.Value().size() != 1) return "run " + run.id + ": the saved scenario gives several runs";
    const harness::Run& reloaded = again.Value().front();
    if (std::string difference = ScenarioDifference(run.scenario, reloaded.scenario); !difference.empty()) {
      return "run " + run.id + ": the reloaded model differs in " + difference;
    }
    if (reloaded.timeStep != run.timeStep || reloaded.steps != run.steps ||
        reloaded.iterations != run.iterations) {
      return "run " + run.id + ": the reloaded stepping differs";
    }
    auto third = harness::ParseScenarioText(harness::ScenarioToJson(reloaded.scenario), "fuzz.json");
    if (!third || !ScenarioDifference(reloaded.scenario, third.Value().front().scenario).empty()) {
      return "run " + run.id + ": a second save and load is not stable";
    }
  }
  return {};
}

std::string CheckShardMerge(std::string_view text) {
  std::vector<harness::ShardFile> shards;
  std::size_t start = 0;
  while (start <= text.size() && shards.size() < 16) {
    std::size_t end = text.find("\n----\n", start);
    const std::string_view part = text.substr(start, end == std::string_view::npos ? end : end - start);
    auto shard = harness::ShardFromJson(part);
    if (shard) {
      // Writing a parsed shard and reading it back is the identity.
      const std::string written = harness::ShardToJson(shard.Value());
      auto back = harness::ShardFromJson(written);
      if (!back) return "a written shard does not read back: " + back.GetError().message;
      if (harness::ShardToJson(back.Value()) != written) return "a shard's write-read-write is not stable";
      shards.push_back(std::move(shard).Value());
    } else if (!shard.GetError().message.starts_with("shard file: ")) {
      return "a shard error without its prefix: " + shard.GetError().message.substr(0, 80);
    }
    if (end == std::string_view::npos) break;
    start = end + 6;
  }
  if (shards.empty()) return {};
  auto merged = harness::MergeShards(shards);
  std::vector<harness::ShardFile> reversed(shards.rbegin(), shards.rend());
  auto mergedReversed = harness::MergeShards(reversed);
  if (!merged) {
    if (!merged.GetError().message.starts_with("merge: ")) return "a merge error without its prefix";
    if (mergedReversed) return "the merge succeeds in one order and fails in the other";
    return {};
  }
  if (!mergedReversed) return "the merge fails in reverse order: " + mergedReversed.GetError().message;
  std::size_t total = 0;
  for (const harness::ShardFile& shard : shards) total += shard.results.results.size();
  if (merged.Value().results.size() != total) return "the merge lost or invented results";
  if (harness::ResultsToJson(merged.Value()) != harness::ResultsToJson(mergedReversed.Value())) {
    return "the merged results depend on the shards' order";
  }
  return {};
}

}  // namespace talus::fuzz
