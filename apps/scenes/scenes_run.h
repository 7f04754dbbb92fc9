// The run of talus-scenes: every (scene, parameter) job on every engine,
// once per setting (thread count for the Talus engines, iteration count,
// substep count), each setting a series of --repeats runs, each run one
// output line (scenes_output.h).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "scenes_options.h"
#include "talus/harness/backend/backend.h"

namespace talus::scenes {

/// Runs everything `options` asks for on `engines`. `registries` holds one
/// registry per --threads count: a Talus backend's worlds take their thread
/// count from the registry that builds them; every peer is built from the
/// first. 0 when every run ran, 1 when one failed (said on stderr, the
/// others still run) or stdout could not be written (the run stops).
int RunScenes(const ScenesOptions& options, const std::vector<std::string>& engines,
              const std::map<int, harness::BackendRegistry>& registries);

}  // namespace talus::scenes
