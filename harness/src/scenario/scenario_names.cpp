// The names scenario files write for the world's choices, both directions
// (scenario.h, scenario_names.h).
#include "scenario/scenario_names.h"

namespace talus::harness {

const char* BroadPhaseChoiceName(BroadPhaseChoice choice) {
  switch (choice) {
    case BroadPhaseChoice::Auto:
      return "auto";
    case BroadPhaseChoice::UniformGrid:
      return "uniform_grid";
    case BroadPhaseChoice::AabbTree:
      return "aabb_tree";
    case BroadPhaseChoice::BruteForce:
      return "brute_force";
  }
  return "auto";
}

const char* BounceTimingChoiceName(BounceTimingChoice choice) {
  switch (choice) {
    case BounceTimingChoice::Auto:
      return "auto";
    case BounceTimingChoice::TimeOfImpact:
      return "time_of_impact";
    case BounceTimingChoice::StepBoundary:
      return "step_boundary";
  }
  return "auto";
}

CombineRule CombineRuleNamed(const std::string& name) {
  if (name == "min") return CombineRule::Min;
  if (name == "max") return CombineRule::Max;
  if (name == "multiply") return CombineRule::Multiply;
  if (name == "average") return CombineRule::Average;
  return CombineRule::Sqrt;
}

Quantity QuantityNamed(const std::string& name) {
  if (name == "orientation") return Quantity::Orientation;
  if (name == "velocity") return Quantity::Velocity;
  if (name == "energy") return Quantity::Energy;
  if (name == "momentum") return Quantity::Momentum;
  if (name == "contacts") return Quantity::Contacts;
  if (name == "penetration") return Quantity::Penetration;
  return Quantity::Position;
}

Motion MotionNamed(const std::string& name) {
  return name == "static" ? Motion::Static : name == "kinematic" ? Motion::Kinematic : Motion::Dynamic;
}

std::optional<BroadPhaseChoice> BroadPhaseChoiceNamed(const std::string& name) {
  for (const BroadPhaseChoice choice : {BroadPhaseChoice::Auto, BroadPhaseChoice::UniformGrid,
                                        BroadPhaseChoice::AabbTree, BroadPhaseChoice::BruteForce}) {
    if (name == BroadPhaseChoiceName(choice)) return choice;
  }
  return std::nullopt;
}

std::optional<BounceTimingChoice> BounceTimingChoiceNamed(const std::string& name) {
  for (const BounceTimingChoice choice :
       {BounceTimingChoice::Auto, BounceTimingChoice::TimeOfImpact, BounceTimingChoice::StepBoundary}) {
    if (name == BounceTimingChoiceName(choice)) return choice;
  }
  return std::nullopt;
}

}  // namespace talus::harness
