// The report's view of the peers' two configurations (docs/testbed-backends.md):
// which settings of each configuration depart from the engine's defaults,
// with their measured effect, and the name of a configuration's tuned
// counterpart ("<name>-tuned"), which report_scorecard.h asks whether it
// removes each FAIL of the defaults.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "talus/harness/run/runner.h"

namespace talus::harness {

/// The tuned counterpart of a backend name ("ode-step" -> "ode-step-tuned");
/// "" for a name that is itself tuned.
std::string TunedName(const std::string& backend);

/// A Markdown table of `settings` that carry an engine default: setting,
/// value here, engine default, measured effect. Empty when none does.
std::string DeparturesTable(const std::vector<Setting>& settings);

}  // namespace talus::harness
