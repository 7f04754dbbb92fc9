// BodySim: the hot per-body state the integrator and the solver read, one
// struct per body in a dense array indexed by body index. At ten cache
// lines (asserted below) it is not small, which is why the Sequential
// Impulses sweeps work on the velocities gathered into SolverBodies
// (solver_body.h) rather than on this array.
//
// Invariants: `orientation` is a unit quaternion; `invInertiaWorld` equals
// R invInertiaLocal R^T for the current orientation (refreshed by
// UpdateWorldInertia after every orientation change); static, kinematic and
// sleeping bodies have invMass == 0 and zero inverse inertia as far as the
// solver is concerned (IsSolverDynamic, which SolverBodies::Add reads), so
// a contact never moves them. The centre of mass `center` is the integrated
// point; the body frame origin is derived from it (center - R localCenter).
//
// Cold bookkeeping (generation, friction, restitution, sleep timers, shape)
// lives apart, in the World's records, so the solver's cache lines carry
// only what it uses.
#pragma once

#include <cstddef>
#include <limits>

#include "talus/body.h"
#include "talus/math.h"

namespace talus {

// The quaternions are aligned to 32 bytes explicitly: Eigen aligns a Quat
// to 16 bytes in an SSE2 translation unit and to 32 in the one compiled
// with -mavx2 (TALUS_SIMD=AVX2, engine/CMakeLists.txt), so without it the
// two would lay BodySim out differently (principalFrame at byte 400 or
// 416) while sharing one definition.
struct alignas(32) BodySim {
  Vec3 center = Vec3::Zero();  ///< centre of mass, world space, metres
  alignas(32) Quat orientation = Quat::Identity();
  Vec3 linearVelocity = Vec3::Zero();   ///< m/s
  Vec3 angularVelocity = Vec3::Zero();  ///< rad/s, world space
  Vec3 force = Vec3::Zero();            ///< N, accumulated for the next step
  Vec3 torque = Vec3::Zero();           ///< N m, accumulated for the next step
  Vec3 localCenter = Vec3::Zero();      ///< centre of mass in the body frame
  Mat3 inertiaLocal = Mat3::Zero();     ///< kg m^2, body axes (for the gyroscopic term)
  Mat3 invInertiaLocal = Mat3::Zero();  ///< 1/(kg m^2), body axes
  Mat3 invInertiaWorld = Mat3::Zero();  ///< 1/(kg m^2), world axes
  /// Principal axes of inertiaLocal: a body-axes vector is principalFrame *
  /// (the same vector in principal axes). Identity for a diagonal inertia.
  alignas(32) Quat principalFrame = Quat::Identity();
  Vec3 principalInertia = Vec3::Zero();  ///< kg m^2, the principal moments
  double invMass = 0.0;                  ///< 1/kg; 0 for static and kinematic bodies
  BodyType type = BodyType::Static;
  bool awake = true;  ///< false while asleep: not integrated, immovable in contacts
  /// Linear velocity at the start of the step and after forces and gravity
  /// (before contacts), m/s: the exact constant-acceleration position update
  /// uses them (integrator.h).
  Vec3 startLinearVelocity = Vec3::Zero();
  Vec3 freeLinearVelocity = Vec3::Zero();
  /// The world angular momentum the last MomentumSplitting drift kept
  /// (kg m^2/s) and the angular velocity it left (rad/s): while nothing
  /// changes w (no torque, impulse or call), the next drift keeps that L
  /// itself instead of I_world w, so a free body's L stays bit-identical
  /// rather than gathering round-off from the conversion each step. NaN when
  /// there is none (SetTransform clears it: a new attitude gives a new L).
  Vec3 keptAngularMomentum = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  Vec3 keptAngularVelocity = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  /// Pseudo-velocities of split impulses, reset every step (m/s, rad/s).
  Vec3 pseudoLinear = Vec3::Zero();
  Vec3 pseudoAngular = Vec3::Zero();

  /// Whether the integrator moves this body this step.
  [[nodiscard]] bool IsMoving() const {
    return type != BodyType::Static && (type == BodyType::Kinematic || awake);
  }
  /// Whether contacts may push this body (a dynamic body that is awake).
  [[nodiscard]] bool IsSolverDynamic() const { return type == BodyType::Dynamic && awake; }
  /// Origin of the body frame, world space.
  [[nodiscard]] Vec3 Origin() const { return center - orientation * localCenter; }

  /// Recomputes invInertiaWorld from the orientation.
  void UpdateWorldInertia() {
    const Mat3 r = orientation.toRotationMatrix();
    invInertiaWorld = r * invInertiaLocal * r.transpose();
  }
};

// One layout in every translation unit, SSE2 or AVX2 (see above): 640
// bytes, ten cache lines. A Sequential Impulses sweep never reads it
// (SolverBodies gathers the velocities, solver_body.h); the integrator, the
// row preparation and the soft step's rows do.
static_assert(sizeof(BodySim) == 640 && alignof(BodySim) == 32, "BodySim: 640 bytes, 32-byte aligned");
static_assert(offsetof(BodySim, principalFrame) == 416 && offsetof(BodySim, pseudoAngular) == 608,
              "BodySim: the same offsets in the SSE2 and the AVX2 translation unit");

}  // namespace talus
