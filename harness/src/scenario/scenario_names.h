// The loader's readers of the names a scenario file writes for the
// scenario model's enums (scenario.h): the schema admits only these names,
// so a reader meets no other. Names are written by CombineRuleName
// (combine_rule.cpp), BroadPhaseChoiceName and BounceTimingChoiceName
// (scenario_names.cpp) and the writer (scenario_writer.cpp).
#pragma once

#include <optional>
#include <string>

#include "talus/harness/scenario/scenario.h"

namespace talus::harness {

/// "min", "max", "multiply", "average"; any other name (only "sqrt" passes
/// the schema) is the square root rule.
CombineRule CombineRuleNamed(const std::string& name);

/// "orientation", "velocity", ...; any other name (only "position" passes
/// the schema) is the position.
Quantity QuantityNamed(const std::string& name);

/// "static", "kinematic"; any other name (only "dynamic" passes the schema)
/// is a dynamic body.
Motion MotionNamed(const std::string& name);

/// The choice BroadPhaseChoiceName writes as `name`, or nothing.
std::optional<BroadPhaseChoice> BroadPhaseChoiceNamed(const std::string& name);

/// The choice BounceTimingChoiceName writes as `name`, or nothing.
std::optional<BounceTimingChoice> BounceTimingChoiceNamed(const std::string& name);

}  // namespace talus::harness
