// Degenerate bodies, refused at load before any engine sees them (the
// loader's semantic checks, body_mapping.cpp): a hull too small or with
// no volume for its extent, a mass that is zero, denormal or not finite,
// an inertia that is not positive definite. Each such body made a peer
// abort or return NaN (docs/testbed-backends.md, "Degenerate bodies"); the
// file's author gets the body and the reason instead.
#pragma once

#include <optional>
#include <string>

#include "talus/harness/scenario/scenario.h"

namespace talus::harness {

/// Smallest volume of a hull relative to the cube of its extent (the
/// diagonal of its points' bounding box). A slab of thickness t and side L
/// has about 0.35 t / L, so this refuses slabs thinner than about 3e-9 of
/// their size (a needle of radius r: about (r / L)^2, radius below 3e-5 L).
/// Why there: a side face of height t is spanned by edges of lengths t and
/// L, so its normal, computed from them, carries a round-off of about
/// epsilon L / t, 7e-8 rad at t = 3e-9 L; below that it passes the SAT's
/// 1e-7 face-preference band, and the face's direction is noise to every
/// engine (ODE's quaternion normalisation failed on such input).
inline constexpr double kMinHullRelativeVolume = 1e-9;

/// Smallest principal moment of inertia relative to the largest. The
/// symmetric eigen solver's answers are exact to a few epsilon of the
/// largest, so a smallest moment below 64 epsilon of it has no reliable
/// sign: the inertia is not positive definite as far as any engine can
/// tell (ODE's dMassCheck refuses it with an abort).
inline constexpr double kMinRelativeMoment = 64.0 * 2.220446049250313e-16;

/// A refusal: the JSON pointer below the body ("/shape/points", "/mass",
/// "" for the body itself) and the reason, naming the body.
struct BodyProblem {
  std::string field;
  std::string reason;
};

/// The first reason `body` is degenerate, or nothing. Expects the
/// magnitudes already checked (CheckMagnitudes: sizes and coordinates
/// within scenario_limits.h).
std::optional<BodyProblem> FindDegenerateBody(const BodySpec& body);

}  // namespace talus::harness
