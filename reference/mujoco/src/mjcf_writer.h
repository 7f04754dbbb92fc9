// A scenario run as MJCF text, for MuJoCo's loader.
//
// Layout: every scenario body i is an MJCF body "b<i>" holding one geom
// "g<i>". A dynamic body's frame is its centre of mass on its principal axes
// (pos X_com = p + R c, quat R P, with c and P from ComputeBodyMass), with a
// free joint and an explicit <inertial> (mass and principal moments), so
// every peer gets the same mass properties; its geom sits at the scenario
// frame inside it (pos -P^T c, quat P^T). A static body is a fixed body
// (no joint) at the scenario frame; a kinematic one the same as a mocap
// body, which the backend moves. A hull is a mesh asset "m<i>" of the
// scenario's points in the body frame; MuJoCo's compiler takes their convex
// hull (qhull) for collision.
//
// Materials: MuJoCo mixes two geoms' friction by the maximum and their
// solref by an average; the scenario's combine rules may want another value.
// Every body pair whose scenario values differ from what MuJoCo's mixing
// gives is excluded from the automatic pairs and added back as an explicit
// <pair> with the scenario's combined friction and solref, so the physics
// asked is the physics run; uniform materials need no pair at all.
//
// Options: what the scenario says (time step, gravity, iterations) and what
// the profile changes; every other option keeps MuJoCo's default. Numbers
// are written in shortest round-trip form, so the model holds exactly the
// scenario's doubles.
#pragma once

#include <span>
#include <string>

#include "talus/harness/scenario/scenario.h"
#include "talus/reference/body_mass.h"
#include "talus/reference/mujoco_backend.h"
#include "talus/result.h"

namespace talus::reference {

/// Largest number of explicit contact pairs a scenario may need (see above):
/// each costs a collision test every step, so a world of many bodies with
/// mixed materials is refused rather than run quadratically.
inline constexpr int kMujocoMaxExplicitPairs = 20000;

/// Contact slots (nconmax) per dynamic body, plus kMujocoBaseContacts. A
/// box on a box yields up to 8 points; a resting cube in a stack touches
/// the one below and above it, a pyramid cube four below and four above.
inline constexpr int kMujocoContactsPerBody = 16;
inline constexpr int kMujocoBaseContacts = 100;

/// The MJCF model of a run and what the writer decided.
struct MjcfModel {
  std::string text;
  int explicitPairs = 0;  ///< body pairs with their own <pair> (combine rules)
  int nconmax = 0;        ///< contact slots
  int njmax = 0;          ///< constraint rows
};

/// The MJCF of `run` for `profile`; `masses` are ComputeBodyMass of each
/// body in order. Fails when the scenario needs more than
/// kMujocoMaxExplicitPairs pairs.
Result<MjcfModel> WriteMjcf(const harness::Run& run, std::span<const BodyMass> masses,
                            const MujocoProfile& profile);

}  // namespace talus::reference
