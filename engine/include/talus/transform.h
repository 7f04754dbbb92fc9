// Transform: where a body (or a shape on it) is in the world, as a rigid
// motion: first rotate about the local origin, then translate.
//
// world = rotation * local + position. The rotation is a unit quaternion;
// functions that take a Transform assume it is normalised (callers normalise
// after integrating orientation).
#pragma once

#include "talus/math.h"

namespace talus {

/// A rigid motion from a local frame to the world frame.
struct Transform {
  Vec3 position = Vec3::Zero();      ///< metres, the local origin in world space
  Quat rotation = Quat::Identity();  ///< unit quaternion, local axes in world space

  /// The identity transform (local frame = world frame).
  static Transform Identity() { return {}; }

  /// A local point in world space (metres).
  [[nodiscard]] Vec3 Apply(const Vec3& localPoint) const { return rotation * localPoint + position; }

  /// A local direction in world space (rotation only).
  [[nodiscard]] Vec3 Rotate(const Vec3& localVector) const { return rotation * localVector; }

  /// A world point in the local frame (the inverse of Apply).
  [[nodiscard]] Vec3 ApplyInverse(const Vec3& worldPoint) const {
    return rotation.conjugate() * (worldPoint - position);
  }

  /// A world direction in the local frame (the inverse of Rotate).
  [[nodiscard]] Vec3 RotateInverse(const Vec3& worldVector) const {
    return rotation.conjugate() * worldVector;
  }

  /// The transform that undoes this one.
  [[nodiscard]] Transform Inverse() const {
    const Quat inverse = rotation.conjugate();
    return {.position = -(inverse * position), .rotation = inverse};
  }
};

/// Composition: (outer * inner).Apply(p) == outer.Apply(inner.Apply(p)).
inline Transform operator*(const Transform& outer, const Transform& inner) {
  return {.position = outer.Apply(inner.position), .rotation = outer.rotation * inner.rotation};
}

}  // namespace talus
