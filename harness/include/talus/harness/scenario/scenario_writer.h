// Writing a scenario model back as a scenario file: the inverse of the
// loader (scenario_loader.h) for one resolved scenario.
//
// ParseScenarioText(ScenarioToJson(s)) gives back `s` (one run, no sweeps):
// every number is written in its shortest round-trip form, the duration as
// a step count, orientations as quaternions and every default explicitly,
// so nothing depends on the loader's defaults staying the same. Only the
// file name (Scenario::file) is not part of the text. Unit vectors the
// loader normalises (orientations, sliding directions, hull_rest normals)
// come back within an ulp or two, since normalising a unit vector again may
// move its last bit. The fuzz target scenario_loader checks the round trip
// (docs/fuzzing.md).
#pragma once

#include <string>

#include "talus/harness/scenario/scenario.h"

namespace talus::harness {

/// The scenario as scenario-file JSON (2-space indented, trailing newline).
std::string ScenarioToJson(const Scenario& scenario);

}  // namespace talus::harness
