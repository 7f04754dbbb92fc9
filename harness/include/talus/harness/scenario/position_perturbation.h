// Round-off-sized moves of a scenario's initial state: the probe behind
// issue 12's perturbed benchmark repeats (scenes/bench_perturb.h) and the
// sweep's noise floor (sweep/perturbed_copies.h). A verdict is only worth
// judging code by if it does not hang on the last bits of the initial
// state; PerturbDynamicPositions moves every dynamic body's initial
// position by an independent uniform offset in [-amount, +amount) per
// axis, drawn from SplitMix64 (support/split_mix64.h) so that the same
// seed gives the same scene bit for bit on every platform.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "talus/harness/scenario/scenario.h"
#include "talus/result.h"

namespace talus::harness {

/// Largest perturbation accepted, metres. The probe is for round-off-sized
/// changes; above 1 mm the cubes of a pyramid layer (which touch exactly)
/// would start up to 2 mm inside each other, and the run would measure a
/// different scene rather than the same one's sensitivity.
inline constexpr double kMaxPositionPerturbation = 1e-3;

/// Why `amount` is not a usable perturbation (NaN, infinite, negative or
/// above kMaxPositionPerturbation), naming the value, or nothing when it is.
std::optional<std::string> PositionPerturbationProblem(double amount);

/// The seed of repeat `repeat` (0-based) of a series seeded with `seed`:
/// seed + repeat, modulo 2^64. SplitMix64 streams from neighbouring seeds
/// share no values in any practical length (each is a bijective mix of a
/// counter advanced by the golden-ratio gamma).
std::uint64_t RepeatSeed(std::uint64_t seed, int repeat);

/// `scene` with every dynamic body's position moved by
/// amount * (2 u - 1) on x, then y, then z, u = SplitMix64(seed).NextUniform()
/// drawn in body order (static and kinematic bodies draw nothing and stay
/// put). An amount of 0 returns the scene unchanged, bit for bit. A bad
/// amount (PositionPerturbationProblem) is an Error and nothing is changed.
Result<Scenario> PerturbDynamicPositions(Scenario scene, double amount, std::uint64_t seed);

}  // namespace talus::harness
