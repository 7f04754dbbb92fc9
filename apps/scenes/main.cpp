// talus-scenes: runs the reference benchmark scenes (pyramid, hull_pile;
// docs/bench-scenes.md) through Talus and its peers in one invocation and
// prints one machine-readable line per scene, parameter and engine, so that
// speed ratios are taken on the same machine at the same moment.
//
//   talus-scenes --scene pyramid --param 15 --engines bullet,ode-quickstep
//   talus-scenes --series --format jsonl      (every scene's scaling series)
//   talus-scenes --scene pyramid --param 20 --engines talus-coloured --threads 1,2
//   talus-scenes --scene pyramid --engines talus,bullet --perturb 1e-9 --repeats 10
//       (each repeat from initial positions moved by up to 1e-9 m; the spread
//       and whether the verdict held in every repeat go to stderr)
//   talus-scenes --scene pyramid --param 10 --iterations 0,4,8,16 --substeps 1,2
//       (one line per engine, iteration count and substep count: total time
//       against drift or penetration over each engine's settings)
//
// The cost of a run is its total wall time (and the mean step, total /
// steps), with the longest step beside it; never a median over the steps of
// one run (docs/bench-scenes.md, "Cost").
// With a list of thread counts each Talus engine runs once per count, one
// right after the other, so the speed-ups compare runs minutes apart; every
// peer runs once, on one thread.
//
// The options and their checks are scenes_options.cpp's, the run
// scenes_run.cpp's, the output lines scenes_output.cpp's.
#include <map>

#include "scenes_options.h"
#include "scenes_run.h"
#include "talus/reference/all_backends.h"

int main(int argc, char** argv) {
  using namespace talus::scenes;
  ScenesOptions options;
  if (const std::optional<int> exit = ParseScenesOptions(argc, argv, options)) return *exit;
  if (!CheckFlagCombinations(options)) return kExitUsage;
  // One registry per thread count: a Talus backend's worlds take their
  // thread count from the registry that builds them.
  std::map<int, talus::harness::BackendRegistry> registries;
  for (int threads : options.threads) registries.emplace(threads, talus::reference::MakeAllBackends(threads));
  const std::optional<std::vector<std::string>> engines = CheckedEngines(options, registries.begin()->second);
  if (!engines) return kExitUsage;
  return RunScenes(options, *engines, registries);
}
