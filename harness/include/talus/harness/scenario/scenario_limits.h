// The bounds every count and magnitude read from a scenario file or the
// command line is checked against where it is read (docs/scenarios.md,
// "Limits"). Each exists so that a careless or hostile input gets a clear
// refusal naming the value and the limit instead of an integer overflow, a
// runaway allocation, an engine assertion or a silent non-finite result.
#pragma once

#include <cstddef>

namespace talus::harness {

/// Steps of one run, including a converged reference's steps x divisor and
/// a stepping sweep's round(duration / h): a billion keeps every step index
/// an int and a run under a day at microseconds per step.
inline constexpr long long kMaxSteps = 1'000'000'000;

/// Runs one scenario file's sweep grid, or a stepping expansion, may make:
/// more would not finish and would not fit a report. Checked before a run
/// is built, from the grid's sizes.
inline constexpr std::size_t kMaxRuns = 100'000;

/// Deepest nesting of arrays and objects in a scenario file. A real file
/// nests about 6 deep; the recursive walks (schema check, sweep labels)
/// must not be able to overflow the stack.
inline constexpr int kMaxJsonDepth = 64;

/// Most threads `--jobs` may ask for.
inline constexpr int kMaxJobs = 1024;

/// Largest |coordinate| of a position or hull point and largest half extent
/// or radius, metres: Talus's World refuses to step a body beyond 1e9 m, and
/// the peers' collision arithmetic overflows well before 1e154.
inline constexpr double kMaxLength = 1e9;

/// Smallest half extent or sphere radius, metres: below it the inertia
/// (m r^2) of a body of ordinary mass reaches 1e-12 of its mass and the
/// peers' solvers divide by it (Bullet gave NaN poses for 1e-200).
inline constexpr double kMinLength = 1e-6;

/// Largest initial speed, and largest rim speed |omega| r of a spinning
/// body, m/s: the speed of light, beyond which rigid-body mechanics is not
/// the model.
inline constexpr double kMaxSpeed = 299'792'458.0;

/// How far a quaternion written in a scenario file (a body's orientation,
/// a state_at truth's) may be from unit norm and still be taken as a
/// rotation. A value written to 7 significant digits (0.7071068) is off by
/// up to 5e-8 per component, so its norm by at most about 1e-7; 1e-6 leaves
/// room for that and refuses anything that is not meant as a unit
/// quaternion. Not a tolerance on any engine's result.
inline constexpr double kUnitQuaternionTolerance = 1e-6;

/// Largest |gravity|, m/s^2: at 1e9 a body falls 1e9 m (the world bound) in
/// under 1.5 s, and beyond ~1e154 the norm itself overflows.
inline constexpr double kMaxGravity = 1e9;

}  // namespace talus::harness
