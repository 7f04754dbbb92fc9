// MakeShardIdentity (shards.h): what shards must share to be merged. The
// digest covers each run's scenario as the scenario writer prints it, so
// it changes with any field of any scenario, not only with the file names.
#include <cstdint>
#include <cstdio>
#include <string_view>
#include <unordered_set>

#include "talus/harness/scenario/scenario_writer.h"
#include "talus/harness/support/build_id.h"
#include "talus/harness/sweep/shards.h"

namespace talus::harness {
namespace {

// FNV-1a, 64 bits: a fingerprint against accidents (a different scenario
// folder, an edited file), not against forgery.
class Fnv1a64 {
 public:
  void Add(std::string_view text) {
    for (const char c : text) {
      m_hash ^= static_cast<unsigned char>(c);
      m_hash *= 0x100000001b3ULL;
    }
    // A separator, so that ("ab", "c") and ("a", "bc") differ.
    m_hash ^= 0xffU;
    m_hash *= 0x100000001b3ULL;
  }
  [[nodiscard]] std::string Hex() const {
    char text[17];
    std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(m_hash));
    return text;
  }

 private:
  std::uint64_t m_hash = 0xcbf29ce484222325ULL;
};

}  // namespace

ShardIdentity MakeShardIdentity(const std::vector<Run>& runs, const std::vector<double>& timeSteps,
                                const std::vector<int>& iterations) {
  ShardIdentity identity;
  identity.build = BuildId();
  identity.timeSteps = timeSteps;
  identity.iterations = iterations;
  std::unordered_set<std::string> seen;
  Fnv1a64 digest;
  for (const Run& run : runs) {
    if (seen.insert(run.scenario.name).second) identity.scenarios.push_back(run.scenario.name);
    char stepping[64];
    std::snprintf(stepping, sizeof(stepping), "%.17g %d %d", run.timeStep, run.iterations, run.steps);
    digest.Add(run.id);
    digest.Add(stepping);
    digest.Add(ScenarioToJson(run.scenario));
  }
  identity.runsDigest = digest.Hex();
  return identity;
}

}  // namespace talus::harness
