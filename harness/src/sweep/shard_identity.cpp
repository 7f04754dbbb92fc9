// MakeShardIdentity (shards.h): what shards must share to be merged. The
// digest covers each run's scenario as the scenario writer prints it, so
// it changes with any field of any scenario, not only with the file names.
#include <cstdio>
#include <unordered_set>

#include "support/fnv1a.h"
#include "talus/harness/scenario/scenario_writer.h"
#include "talus/harness/support/build_id.h"
#include "talus/harness/sweep/shards.h"

namespace talus::harness {

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
