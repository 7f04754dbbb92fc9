// Talus public math vocabulary: Eigen types in double precision.
//
// The testbed measures accuracy, so the engine computes in double throughout.
// Positions are metres, angles radians, everything else SI unless a name
// says otherwise.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace talus {

using Vec3 = Eigen::Vector3d;     ///< A point or direction, metres or unitless.
using Mat3 = Eigen::Matrix3d;     ///< A 3x3 matrix (rotation, inertia tensor).
using Quat = Eigen::Quaterniond;  ///< A unit quaternion for orientation.

/// A plane n . x = offset. `normal` is unit length; points with
/// n . x > offset are in front of (outside) the plane.
struct Plane {
  Vec3 normal = Vec3::UnitY();
  double offset = 0.0;  ///< metres, signed distance of the plane from the origin

  /// Signed distance of `point` from the plane, positive in front.
  [[nodiscard]] double SignedDistance(const Vec3& point) const { return normal.dot(point) - offset; }
};

/// An axis-aligned box given by its smallest and largest corner (metres).
struct Aabb {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
};

/// A sphere by centre and radius (metres).
struct Sphere {
  Vec3 center = Vec3::Zero();
  double radius = 0.0;
};

}  // namespace talus
