// Round-off-sized moves of a scenario's initial state (see
// talus/harness/scenario/position_perturbation.h).
#include "talus/harness/scenario/position_perturbation.h"

#include "talus/harness/support/number_text.h"
#include "talus/harness/support/split_mix64.h"

namespace talus::harness {

std::optional<std::string> PositionPerturbationProblem(double amount) {
  // Written so that NaN fails the test too.
  if (!(amount >= 0.0 && amount <= kMaxPositionPerturbation)) {
    return "perturbation " + FormatNumber(amount) + " m: must be a number in [0, " +
           FormatNumber(kMaxPositionPerturbation) + "] m";
  }
  return std::nullopt;
}

std::uint64_t RepeatSeed(std::uint64_t seed, int repeat) {
  return seed + static_cast<std::uint64_t>(repeat);  // modulo 2^64 by definition
}

Result<Scenario> PerturbDynamicPositions(Scenario scene, double amount, std::uint64_t seed) {
  if (auto problem = PositionPerturbationProblem(amount)) return Error{*problem};
  if (amount == 0.0) return scene;  // bit for bit: not even -0.0 is added
  SplitMix64 stream(seed);
  for (BodySpec& body : scene.bodies) {
    if (body.motion != Motion::Dynamic) continue;
    for (int axis = 0; axis < 3; ++axis) {
      body.position[axis] += amount * (2.0 * stream.NextUniform() - 1.0);
    }
  }
  return scene;
}

}  // namespace talus::harness
