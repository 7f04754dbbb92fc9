// The report's view of the peers' two configurations (docs/testbed-backends.md):
// which settings of each configuration depart from the engine's defaults,
// with their measured effect, and, for each FAIL of a peer's defaults,
// whether its tuned configuration ("<name>-tuned") removes it.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "talus/harness/runner.h"

namespace talus::harness {

/// The tuned counterpart of a backend name ("ode-step" -> "ode-step-tuned");
/// "" for a name that is itself tuned.
std::string TunedName(const std::string& backend);

/// Markdown bullet lines, one per failed truth of a backend in `backends`
/// whose tuned counterpart ran the same run: "removed by" or "not removed
/// by" it, with the tuned error. Empty when no such FAIL.
std::string TunedVerdictLines(const std::vector<std::string>& backends,
                              const std::map<std::string, const RunResult*>& byBackend);

/// A Markdown table of `settings` that carry an engine default: setting,
/// value here, engine default, measured effect. Empty when none does.
std::string DeparturesTable(const std::vector<Setting>& settings);

}  // namespace talus::harness
