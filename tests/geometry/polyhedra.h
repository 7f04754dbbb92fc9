// Test polyhedra built through Hull::FromPolygons, for the mass property and
// query tests: closed-form shapes (box, regular tetrahedron, octahedron,
// UV sphere, prisms) and random affine images of them, which stay convex
// with planar faces. Random shapes come from a caller-owned std::mt19937_64
// with a fixed seed, so every run sees the same polyhedra.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include "talus/hull.h"
#include "talus/math.h"

namespace talus::test {

/// Vertices and counter-clockwise face loops, before validation.
struct Polygons {
  std::vector<Vec3> vertices;
  std::vector<std::vector<int>> faces;
};

/// Reverses any face whose Newell normal points towards the vertex average;
/// correct for convex shapes, which is all this file makes.
inline void OrientOutward(Polygons& shape) {
  Vec3 center = Vec3::Zero();
  for (const Vec3& v : shape.vertices) center += v;
  center /= static_cast<double>(shape.vertices.size());
  for (auto& loop : shape.faces) {
    Vec3 normal = Vec3::Zero();
    for (std::size_t i = 0; i < loop.size(); ++i) {
      normal += shape.vertices[static_cast<std::size_t>(loop[i])].cross(
          shape.vertices[static_cast<std::size_t>(loop[(i + 1) % loop.size()])]);
    }
    if (normal.dot(shape.vertices[static_cast<std::size_t>(loop[0])] - center) < 0.0) {
      std::reverse(loop.begin(), loop.end());
    }
  }
}

/// Validation tolerance (metres) for the test shapes: rotated and scaled
/// vertices leave faces planar only up to round-off (~1e-14 m at the 20 m
/// these shapes reach), while the smallest real gap between face planes is
/// ~1e-2 m, so 1e-10 m separates the two by orders of magnitude.
constexpr double kShapeTolerance = 1e-10;

/// Validates through Hull::FromPolygons and fails the test on an error.
inline Hull MakeHull(Polygons shape, double tolerance = kShapeTolerance) {
  auto hull = Hull::FromPolygons(std::move(shape.vertices), shape.faces, tolerance);
  EXPECT_TRUE(hull) << hull.GetError().message;
  return std::move(hull).Value();
}

/// Axis-aligned box with half extents `e` centred on `center`.
inline Polygons BoxPolygons(const Vec3& e, const Vec3& center = Vec3::Zero()) {
  Polygons shape;
  for (int i = 0; i < 8; ++i) {
    shape.vertices.push_back(
        center + Vec3((i & 1) ? e.x() : -e.x(), (i & 2) ? e.y() : -e.y(), (i & 4) ? e.z() : -e.z()));
  }
  shape.faces = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3}, {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
  return shape;
}

/// Regular tetrahedron with edge length `edge`, centred on the origin.
inline Polygons TetrahedronPolygons(double edge) {
  const double s = edge / (2.0 * std::numbers::sqrt2);  // corners of a cube of half side s
  Polygons shape{.vertices = {{s, s, s}, {s, -s, -s}, {-s, s, -s}, {-s, -s, s}},
                 .faces = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}};
  OrientOutward(shape);
  return shape;
}

/// Regular octahedron with vertices at distance `a` on the axes.
inline Polygons OctahedronPolygons(double a) {
  Polygons shape{.vertices = {{a, 0, 0}, {-a, 0, 0}, {0, a, 0}, {0, -a, 0}, {0, 0, a}, {0, 0, -a}},
                 .faces = {}};
  for (int x : {0, 1}) {
    for (int y : {2, 3}) {
      for (int z : {4, 5}) shape.faces.push_back({x, y, z});
    }
  }
  OrientOutward(shape);
  return shape;
}

/// A UV sphere of radius `r` inscribed in the sphere: `bands` latitude
/// bands and `sectors` longitudes; triangle fans at the poles, quads in
/// between. Each quad spans two parallel horizontal chords symmetric about
/// its mid-longitude plane (an isosceles trapezoid), so it is planar.
inline Polygons UvSpherePolygons(double r, int bands, int sectors) {
  Polygons shape;
  shape.vertices.emplace_back(0.0, 0.0, r);
  for (int i = 1; i < bands; ++i) {
    const double theta = std::numbers::pi * i / bands;
    for (int j = 0; j < sectors; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / sectors;
      shape.vertices.emplace_back(r * std::sin(theta) * std::cos(phi), r * std::sin(theta) * std::sin(phi),
                                  r * std::cos(theta));
    }
  }
  shape.vertices.emplace_back(0.0, 0.0, -r);
  const int south = static_cast<int>(shape.vertices.size()) - 1;
  const auto ring = [&](int i, int j) { return 1 + (i - 1) * sectors + (j % sectors); };
  for (int j = 0; j < sectors; ++j) {
    shape.faces.push_back({0, ring(1, j), ring(1, j + 1)});
    for (int i = 1; i + 1 < bands; ++i) {
      shape.faces.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
    shape.faces.push_back({south, ring(bands - 1, j + 1), ring(bands - 1, j)});
  }
  OrientOutward(shape);
  return shape;
}

/// A right prism of height `height` over a convex polygon through the given
/// angles (radians, increasing in [0, 2 pi)) on the unit circle.
inline Polygons PrismPolygons(const std::vector<double>& angles, double height) {
  Polygons shape;
  const int n = static_cast<int>(angles.size());
  for (double z : {-0.5 * height, 0.5 * height}) {
    for (double a : angles) shape.vertices.emplace_back(std::cos(a), std::sin(a), z);
  }
  std::vector<int> bottom;
  std::vector<int> top;
  for (int i = 0; i < n; ++i) {
    bottom.push_back(n - 1 - i);
    top.push_back(n + i);
    shape.faces.push_back({i, (i + 1) % n, n + (i + 1) % n, n + i});
  }
  shape.faces.push_back(bottom);
  shape.faces.push_back(top);
  OrientOutward(shape);
  return shape;
}

/// A uniformly random rotation (normalised Gaussian quaternion).
inline Mat3 RandomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> gauss;
  Quat q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
  q.normalize();
  return q.toRotationMatrix();
}

/// A random direction on the unit sphere.
inline Vec3 RandomDirection(std::mt19937_64& rng) {
  std::normal_distribution<double> gauss;
  return Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
}

/// Applies x -> linear x + shift to every vertex; reorients faces if the
/// map mirrors.
inline Polygons Transformed(Polygons shape, const Mat3& linear, const Vec3& shift) {
  for (Vec3& v : shape.vertices) v = linear * v + shift;
  OrientOutward(shape);
  return shape;
}

/// One of the base shapes above with at most 14 vertices, chosen at random.
inline Polygons RandomBaseShape(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 4);
  std::uniform_real_distribution<double> size(0.3, 2.0);
  switch (kind(rng)) {
    case 0:
      return BoxPolygons(Vec3(size(rng), size(rng), size(rng)));
    case 1:
      return TetrahedronPolygons(size(rng));
    case 2:
      return OctahedronPolygons(size(rng));
    case 3:
      return UvSpherePolygons(size(rng), 3, 4 + static_cast<int>(rng() % 3));
    default: {
      // Sorted random angles with gaps of at least 0.3 rad keep the
      // polygon convex and its vertices apart.
      const int n = 3 + static_cast<int>(rng() % 5);
      std::vector<double> angles;
      const double slack = 2.0 * std::numbers::pi - 0.3 * n;
      std::uniform_real_distribution<double> unit(0.0, 1.0);
      std::vector<double> cuts;
      for (int i = 0; i < n; ++i) cuts.push_back(unit(rng));
      double sum = 0.0;
      for (double c : cuts) sum += c;
      double angle = unit(rng);
      for (int i = 0; i < n; ++i) {
        angles.push_back(angle);
        angle += 0.3 + slack * cuts[static_cast<std::size_t>(i)] / sum;
      }
      return PrismPolygons(angles, size(rng));
    }
  }
}

/// A random base shape under a random rotation, a random anisotropic
/// scale (0.5 to 2 per axis, so faces stay clearly non-coplanar) and a
/// random shift of up to 10 m per axis.
inline Polygons RandomConvexPolygons(std::mt19937_64& rng, Mat3* linearOut = nullptr) {
  std::uniform_real_distribution<double> scale(0.5, 2.0);
  std::uniform_real_distribution<double> shift(-10.0, 10.0);
  const Mat3 linear =
      RandomRotation(rng) * Vec3(scale(rng), scale(rng), scale(rng)).asDiagonal() * RandomRotation(rng);
  if (linearOut != nullptr) *linearOut = linear;
  Polygons base = RandomBaseShape(rng);
  return Transformed(std::move(base), linear, Vec3(shift(rng), shift(rng), shift(rng)));
}

}  // namespace talus::test
