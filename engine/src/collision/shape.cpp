// Shape creation, bounding volumes, support points and mass properties.
//
// Box and sphere mass properties are closed form; a general hull goes
// through talus::ComputeMassProperties (divergence theorem, exact).
#include "talus/shape.h"

#include <cassert>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <utility>

#include "talus/hull_queries.h"

namespace talus {
namespace {

std::optional<Error> CheckDensity(double density) {
  if (!std::isfinite(density) || density <= 0.0) {
    return Error{"density must be finite and > 0 kg/m^3, got " + std::to_string(density)};
  }
  return std::nullopt;
}

}  // namespace

Result<Shape> Shape::CreateHull(std::shared_ptr<const Hull> hull) {
  if (!hull) return Error{"hull shape: the hull pointer is null"};
  Shape shape;
  shape.m_type = ShapeType::Hull;
  shape.m_localAabb = ComputeAabb(*hull);
  // The sphere about the AABB centre: one pass, no dependence on the mass
  // properties, and within sqrt(3) of the tightest sphere.
  const Vec3 center = 0.5 * (shape.m_localAabb.min + shape.m_localAabb.max);
  double radiusSquared = 0.0;
  for (const Vec3& v : hull->Vertices()) radiusSquared = std::max(radiusSquared, (v - center).squaredNorm());
  shape.m_localSphere = {.center = center, .radius = std::sqrt(radiusSquared)};
  shape.m_hull = std::move(hull);
  return shape;
}

Result<Shape> Shape::CreateBox(const Vec3& halfExtents) {
  static constexpr const char* kAxisNames[3] = {"x", "y", "z"};
  for (int axis = 0; axis < 3; ++axis) {
    const double e = halfExtents[axis];
    if (!std::isfinite(e) || e <= 0.0) {
      return Error{std::string("box shape: half extent ") + kAxisNames[axis] +
                   " must be finite and > 0 m, got " + std::to_string(e)};
    }
  }
  auto hull = Hull::Box(halfExtents);
  if (!hull) return Error{"box shape: " + hull.GetError().message};
  Shape shape;
  shape.m_type = ShapeType::Box;
  shape.m_hull = std::make_shared<const Hull>(std::move(hull).Value());
  shape.m_halfExtents = halfExtents;
  shape.m_localAabb = {.min = -halfExtents, .max = halfExtents};
  shape.m_localSphere = {.center = Vec3::Zero(), .radius = halfExtents.norm()};
  return shape;
}

Result<Shape> Shape::CreateSphere(double radius) {
  if (!std::isfinite(radius) || radius <= 0.0) {
    return Error{"sphere shape: radius must be finite and > 0 m, got " + std::to_string(radius)};
  }
  Shape shape;
  shape.m_type = ShapeType::Sphere;
  shape.m_radius = radius;
  shape.m_localAabb = {.min = Vec3::Constant(-radius), .max = Vec3::Constant(radius)};
  shape.m_localSphere = {.center = Vec3::Zero(), .radius = radius};
  return shape;
}

const Hull& Shape::GetHull() const {
  assert(m_hull && "GetHull on a sphere shape");
  return *m_hull;
}

Vec3 Shape::Support(const Vec3& localDirection) const {
  switch (m_type) {
    case ShapeType::Sphere: {
      const double length = localDirection.norm();
      if (!(length > 0.0)) return Vec3(0.0, m_radius, 0.0);
      return localDirection * (m_radius / length);
    }
    case ShapeType::Box:
      // The corner in the direction's octant; a zero component picks +.
      return {localDirection.x() < 0.0 ? -m_halfExtents.x() : m_halfExtents.x(),
              localDirection.y() < 0.0 ? -m_halfExtents.y() : m_halfExtents.y(),
              localDirection.z() < 0.0 ? -m_halfExtents.z() : m_halfExtents.z()};
    case ShapeType::Hull:
      break;
  }
  const auto vertices = m_hull->Vertices();
  std::size_t best = 0;
  double bestDot = localDirection.dot(vertices[0]);
  for (std::size_t i = 1; i < vertices.size(); ++i) {
    const double d = localDirection.dot(vertices[i]);
    if (d > bestDot) {
      bestDot = d;
      best = i;
    }
  }
  return vertices[best];
}

Result<MassProperties> Shape::ComputeMass(double density) const {
  if (auto error = CheckDensity(density)) return *error;
  MassProperties props;
  switch (m_type) {
    case ShapeType::Box: {
      // Solid box of sides 2e: I_xx = m (ey^2 + ez^2) / 3 (half extents).
      const Vec3 e2 = m_halfExtents.cwiseProduct(m_halfExtents);
      props.volume = 8.0 * m_halfExtents.prod();
      props.mass = density * props.volume;
      props.inertia =
          (props.mass / 3.0 * Vec3(e2.y() + e2.z(), e2.x() + e2.z(), e2.x() + e2.y())).asDiagonal();
      return props;
    }
    case ShapeType::Sphere: {
      // Solid sphere: V = 4/3 pi r^3, I = 2/5 m r^2 about every axis.
      props.volume = 4.0 / 3.0 * std::numbers::pi * m_radius * m_radius * m_radius;
      props.mass = density * props.volume;
      props.inertia = Mat3::Identity() * (0.4 * props.mass * m_radius * m_radius);
      return props;
    }
    case ShapeType::Hull:
      break;
  }
  return ComputeMassProperties(*m_hull, density);
}

}  // namespace talus
