// A scenario file's "world" to WorldSpec (world_mapping.h).
#include "scenario/world_mapping.h"

#include <cmath>
#include <string>

#include "scenario/scenario_mapping_support.h"
#include "scenario/scenario_names.h"
#include "support/text_util.h"
#include "talus/harness/scenario/scenario_limits.h"
#include "talus/harness/scenario/truth_kind_io.h"

namespace talus::harness {
namespace {

using nlohmann::json;

// The run's length in steps, given as "steps" or as "seconds" rounded to
// whole steps of `timeStep`, within 1 to kMaxSteps.
Result<int> MapDuration(const json& duration, double timeStep, std::string_view file) {
  const std::string limit = std::to_string(kMaxSteps);
  if (duration.contains("steps")) {
    // Read as a double first: a count past the int range must not wrap.
    const double steps = duration["steps"].get<double>();
    if (steps > static_cast<double>(kMaxSteps)) {
      return FieldError(file, "/world/duration/steps",
                        Concat({FormatNumber(steps, 17), " steps is more than the limit of ", limit}));
    }
    return static_cast<int>(steps);
  }
  const double steps = std::round(duration["seconds"].get<double>() / timeStep);
  if (!(steps >= 1.0 && steps <= static_cast<double>(kMaxSteps))) {
    return FieldError(file, "/world/duration/seconds",
                      Concat({"gives ", FormatNumber(steps, 17), " steps; need 1 to ", limit}));
  }
  return static_cast<int>(steps);
}

}  // namespace

Result<WorldSpec> MapWorld(const json& world, std::string_view file) {
  WorldSpec settings;
  if (world.contains("gravity")) settings.gravity = ReadVec3(world["gravity"]);
  if (const double g = ScaleSafeNorm(settings.gravity); g > kMaxGravity) {
    return FieldError(file, "/world/gravity",
                      Concat({"magnitude ", FormatNumber(g), " m/s^2 is more than the limit of ",
                              FormatNumber(kMaxGravity), " m/s^2"}));
  }
  settings.timeStep = world["timeStep"].get<double>();
  if (world.contains("iterations") && world["iterations"].is_number()) {
    settings.iterations = world["iterations"].get<int>();
  }
  auto steps = MapDuration(world["duration"], settings.timeStep, file);
  if (!steps) return steps.GetError();
  settings.steps = steps.Value();
  if (world.contains("frictionCombine"))
    settings.frictionCombine = CombineRuleNamed(world["frictionCombine"].get<std::string>());
  if (world.contains("restitutionCombine"))
    settings.restitutionCombine = CombineRuleNamed(world["restitutionCombine"].get<std::string>());
  settings.gyroscopic = world.value("gyroscopic", true);
  if (world.contains("broadPhase")) {
    if (auto choice = BroadPhaseChoiceNamed(world["broadPhase"].get<std::string>()))
      settings.broadPhase = *choice;
  }
  if (world.contains("bounceTiming")) {
    if (auto choice = BounceTimingChoiceNamed(world["bounceTiming"].get<std::string>()))
      settings.bounceTiming = *choice;
  }
  return settings;
}

}  // namespace talus::harness
