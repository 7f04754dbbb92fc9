// The MuJoCo peer behind the harness's Backend interface: Debian's MuJoCo
// 2.2.2 (libmujoco-dev), in two configurations.
//
// "mujoco" is what a new user gets: the scenario written as MJCF with only
// what the scenario itself says (time step, gravity, iterations, masses,
// friction, restitution) and every engine option at MuJoCo's default
// (semi-implicit Euler, pyramidal cones, Newton solver, soft contacts with
// solref 0.02 1 and solimp 0.9 0.95 0.001 0.5 2). "mujoco-tuned" is the
// documented best practice for the rigid-body physics asked (MuJoCo's
// "Modeling" chapter, solver settings: try elliptic cones; "when contact
// slip is a problem", elliptic cones, a large impratio and Newton with a
// very small tolerance, "say 1e-10", then the noslip solver if that is not
// enough): elliptic cones, impratio 10, tolerance 1e-10, 10 noslip
// iterations, multi-point convex collision (multiccd) and RK4 in worlds
// where no contact can occur (a single body). The implicit integrator and
// a harder solimp were measured and left out. Settings() lists every option
// that differs from the defaults, docs/testbed-backends.md gives each one's
// measured effect.
//
// Every scenario becomes an MJCF text in memory (mjcf_writer.h) loaded
// through a virtual file system; MuJoCo's errors (mju_user_error) and
// warnings (contact buffer full, bad qacc...) become a refused world or a
// failed run, never an exit of the process (mujoco_guard.h). Worlds share
// no state and step on one thread each; a run is deterministic. MuJoCo's
// loader swaps the process-wide mju_user_error while it compiles, so worlds
// are built on one thread at a time: the runner's serial lane for the
// "mujoco" family (both names) does that.
#pragma once

#include <memory>
#include <string>

#include "talus/harness/backend/backend.h"
#include "talus/result.h"

namespace talus::reference {

/// MuJoCo's default contact time constant (solref[0], seconds).
inline constexpr double kMujocoDefaultTimeConstant = 0.02;

/// The damping ratio z of a contact of restitution `e` (in [0, 1]): a damped
/// spring x'' + 2 z w x' + w^2 x = 0 that meets the surface at speed v leaves
/// it at e v after half a damped period, e = exp(-z pi / sqrt(1 - z^2)), so
/// z = -ln e / sqrt(pi^2 + ln^2 e); e = 0 gives 1 (critical damping: no
/// bounce, MuJoCo's default), e = 1 gives 0.
double MujocoDampRatioForRestitution(double e);

/// MuJoCo's solref for a contact of restitution `e` at time step `h`.
/// MuJoCo has no restitution coefficient; its contact is a spring-damper on
/// the penetration (aref = -B v - K I r). For e = 0 this is MuJoCo's default
/// (timeconst 0.02 s, dampratio 1). For e > 0 it is the direct form
/// (-stiffness, -damping): the default contact's stiffness w^2 = 1 / t^2,
/// with t = max(0.02, 2 h) (the default time constant and the floor MuJoCo's
/// refsafe puts under it, so w h <= 1/2 stays stable), and damping 2 z w
/// with z from MujocoDampRatioForRestitution. (The positive form
/// (timeconst, dampratio) would make the spring stiffer as z falls,
/// w = 1 / (timeconst z), unstable at w h > 2.) An approximation: the
/// contact force cannot pull, so the body leaves slightly before the spring
/// is back at its rest length (measured in docs/testbed-backends.md).
struct MujocoSolref {
  double first = kMujocoDefaultTimeConstant;
  double second = 1.0;
};
MujocoSolref MujocoSolrefForRestitution(double e, double timeStep);

/// Largest mjData a world may allocate, bytes. MuJoCo 2.2.2 sizes its
/// constraint arrays for the worst case at mj_makeData: efc_J and efc_JT
/// (njmax x nv), efc_AR (njmax x njmax) and a stack that grows with njmax^2,
/// so memory grows with the square of the contact capacity (the 30 cubes of
/// pyramid H = 4 already take about 0.3 GB). A world above this is refused
/// with its size named, instead of exhausting a shared machine.
inline constexpr double kMujocoMaxDataBytes = 1024.0 * 1024.0 * 1024.0;

/// What a MuJoCo configuration changes from MuJoCo's defaults; an empty or
/// zero field keeps the default.
struct MujocoProfile {
  std::string name;        ///< registry name, reported by Backend::Name
  std::string integrator;  ///< MJCF option/integrator ("implicit", "RK4"); "" = Euler
  /// The integrator of a world where no contact can occur (a single body:
  /// free flight, torque-free tumbling); "" = `integrator`.
  std::string contactFreeIntegrator;
  std::string cone;          ///< MJCF option/cone ("elliptic"); "" = pyramidal
  int noslipIterations = 0;  ///< MJCF option/noslip_iterations; 0 = off
  double impratio = 0.0;     ///< MJCF option/impratio; 0 = MuJoCo's 1
  double tolerance = 0.0;    ///< MJCF option/tolerance (solver); 0 = MuJoCo's 1e-8
  bool multiccd = false;     ///< option/flag multiccd: several points per convex (mesh) pair
};

/// "mujoco": nothing changed.
MujocoProfile MujocoDefaultsProfile();
/// "mujoco-tuned" (see the file comment; docs/testbed-backends.md measures
/// each field's effect).
MujocoProfile MujocoTunedProfile();

/// A MuJoCo world for `run` in `profile` (what the registered factories
/// call; tests use it to measure one option at a time).
Result<std::unique_ptr<harness::Backend>> CreateMujocoBackend(const harness::Run& run,
                                                              const MujocoProfile& profile);

/// Registers "mujoco" (MuJoCo's defaults) and "mujoco-tuned".
void RegisterMujocoBackends(harness::BackendRegistry& registry);

}  // namespace talus::reference
