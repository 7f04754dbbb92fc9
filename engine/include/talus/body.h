// Bodies as the user sees them: a kind (static, kinematic, dynamic), a
// stable id, and a definition struct with defaults from which the World
// creates one.
//
// A body's frame has its origin at `position` and axes given by
// `orientation`; its centre of mass sits at `localCenterOfMass` in that
// frame. Units are SI: metres, kilograms, seconds, radians.
#pragma once

#include <cstdint>
#include <optional>

#include "talus/math.h"
#include "talus/shape.h"

namespace talus {

/// How a body moves.
enum class BodyType {
  Static,     ///< never moves; infinite mass; costs nothing when it touches only statics
  Kinematic,  ///< moves with the velocity the user sets; infinite mass; ignores forces and contacts
  Dynamic,    ///< moved by forces, gravity and contacts; finite positive mass
};

/// A stable handle to a body in a World: the slot index plus the slot's
/// generation when the body was created. Destroying a body bumps its slot's
/// generation, so an old id is recognised as stale and refused, never
/// dereferenced. The default id names no body.
struct BodyId {
  std::int32_t index = -1;       ///< slot in the World's body arrays
  std::uint32_t generation = 0;  ///< the slot's generation at creation

  friend bool operator==(const BodyId&, const BodyId&) = default;
};

/// Everything needed to create a body; every field has a usable default, so
/// `world.CreateBody({.type = BodyType::Dynamic, .position = {0, 4, 0}})`
/// reads as the body it makes. Refused when any number is NaN or infinite.
struct BodyDef {
  /// How the body moves. Default Static (the ground is the most common body).
  BodyType type = BodyType::Static;
  /// Origin of the body frame in world space, metres. Default the origin.
  Vec3 position = Vec3::Zero();
  /// Orientation of the body frame; normalised on creation (must be non-zero).
  Quat orientation = Quat::Identity();
  /// Velocity of the centre of mass, m/s. Default at rest.
  Vec3 linearVelocity = Vec3::Zero();
  /// Angular velocity in world space, rad/s. Default at rest.
  Vec3 angularVelocity = Vec3::Zero();
  /// The collision geometry in the body frame; none (the default) means the
  /// body collides with nothing. Shapes share their hull, so copies are cheap.
  std::optional<Shape> shape = std::nullopt;
  /// Density in kg/m^3. When > 0 (and the body is dynamic with a shape) the
  /// mass, inertia and centre of mass come from the shape and this density,
  /// and `mass`, `localInertia` and `localCenterOfMass` are ignored. Default
  /// 0: use the given mass data. Negative or non-finite is refused.
  double density = 0.0;
  /// Mass in kg, > 0; used by dynamic bodies without a density. Default 1 kg.
  double mass = 1.0;
  /// Inertia tensor about the centre of mass in body axes, kg m^2; must be
  /// symmetric positive definite for dynamic bodies. Default that of a 1 kg
  /// cube of side 1 m (I/6).
  Mat3 localInertia = Mat3::Identity() / 6.0;
  /// Centre of mass in the body frame, metres. Default the body origin.
  Vec3 localCenterOfMass = Vec3::Zero();
  /// Coulomb friction coefficient, >= 0, unitless; combined with the other
  /// body's by WorldSettings::frictionCombine. Default 0.5 (wood-like).
  double friction = 0.5;
  /// Coefficient of restitution in [0, 1], unitless; combined with the other
  /// body's by WorldSettings::restitutionCombine. Default 0 (no bounce).
  double restitution = 0.0;
  /// Whether the body may fall asleep when at rest (WorldSettings::sleeping
  /// must be on too). Default true.
  bool allowSleep = true;
};

/// A snapshot of a body's state, as returned by World::GetBodyState.
struct BodyState {
  BodyType type = BodyType::Static;
  Vec3 position = Vec3::Zero();         ///< body frame origin, metres, world space
  Quat orientation = Quat::Identity();  ///< unit quaternion
  Vec3 centerOfMass = Vec3::Zero();     ///< metres, world space
  Vec3 linearVelocity = Vec3::Zero();   ///< of the centre of mass, m/s
  Vec3 angularVelocity = Vec3::Zero();  ///< rad/s, world space
  double mass = 0.0;                    ///< kg; 0 for static and kinematic bodies
  Mat3 localInertia = Mat3::Zero();     ///< kg m^2 about the centre of mass, body axes; 0 unless dynamic
  bool awake = true;                    ///< false while asleep
};

}  // namespace talus
