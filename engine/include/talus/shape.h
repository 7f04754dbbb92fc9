// Shape: the immutable collision geometry a body carries, in the body's own
// frame. Three kinds: a convex hull, a box (a hull with closed-form fast
// paths) and a sphere (exact routines, no hull).
//
// Shapes are values that share their Hull through a
// std::shared_ptr<const Hull>, so copying a Shape is cheap and many bodies
// may use one hull. A Shape only comes out of a Create function, validated:
// there is no half-built or empty Shape.
#pragma once

#include <memory>

#include "talus/hull.h"
#include "talus/mass_properties.h"
#include "talus/math.h"
#include "talus/result.h"

namespace talus {

/// Which kind of geometry a Shape holds. The values index the narrow
/// phase's dispatch table.
enum class ShapeType {
  Hull = 0,    ///< a general convex polyhedron
  Box = 1,     ///< a box centred on the local origin (also has a Hull)
  Sphere = 2,  ///< a sphere centred on the local origin (no Hull)
};

/// Number of ShapeType values (size of the dispatch table's sides).
inline constexpr int kShapeTypeCount = 3;

class Shape {
 public:
  /// A convex hull shape sharing `hull` (non-null). Fails on a null hull.
  static Result<Shape> CreateHull(std::shared_ptr<const Hull> hull);

  /// A box centred on the origin with the given half extents (metres, each
  /// finite and > 0); refused otherwise with a message naming the axis.
  static Result<Shape> CreateBox(const Vec3& halfExtents);

  /// A sphere centred on the origin of `radius` metres (finite and > 0);
  /// refused otherwise.
  static Result<Shape> CreateSphere(double radius);

  [[nodiscard]] ShapeType Type() const { return m_type; }

  /// Whether the shape is a polyhedron (Hull or Box), i.e. has a Hull.
  [[nodiscard]] bool IsPolyhedron() const { return m_type != ShapeType::Sphere; }

  /// The polyhedron (Hull and Box shapes); only valid when IsPolyhedron().
  [[nodiscard]] const Hull& GetHull() const;

  /// The shared pointer to the polyhedron; null for a sphere.
  [[nodiscard]] const std::shared_ptr<const Hull>& HullPointer() const { return m_hull; }

  /// Half extents in metres (Box only; zero for other kinds).
  [[nodiscard]] const Vec3& HalfExtents() const { return m_halfExtents; }

  /// Radius in metres (Sphere only; zero for other kinds).
  [[nodiscard]] double Radius() const { return m_radius; }

  /// The axis-aligned bounding box in the shape's frame (metres).
  [[nodiscard]] const Aabb& LocalAabb() const { return m_localAabb; }

  /// A bounding sphere in the shape's frame: for a sphere itself, for a box
  /// the circumscribed sphere, for a hull the sphere about the centre of its
  /// AABB through its farthest vertex (cheap, tight for symmetric hulls).
  [[nodiscard]] const Sphere& LocalBoundingSphere() const { return m_localSphere; }

  /// The point of the shape farthest along `localDirection` (shape frame,
  /// need not be unit length; a zero direction gives some surface point).
  [[nodiscard]] Vec3 Support(const Vec3& localDirection) const;

  /// Mass properties of the shape filled with uniform `density` (kg/m^3,
  /// finite and > 0). Box and sphere in closed form; a hull through
  /// talus::ComputeMassProperties (exact). Refuses a bad density.
  [[nodiscard]] Result<MassProperties> ComputeMass(double density) const;

 private:
  Shape() = default;

  ShapeType m_type = ShapeType::Sphere;
  std::shared_ptr<const Hull> m_hull;
  Vec3 m_halfExtents = Vec3::Zero();
  double m_radius = 0.0;
  Aabb m_localAabb;
  Sphere m_localSphere;
};

}  // namespace talus
