// Shapes: refusal of bad parameters, bounding volumes that bound, support
// points against brute force, and mass properties in closed form checked
// against the exact polyhedron integration.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "collision/sat_test_fixtures.h"
#include "talus/mass_properties.h"

namespace talus {
namespace shape_test {

TEST(Shape, BadRadiusExtentsAndHullAreRefusedWithAMessage) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double r : {0.0, -1.0, nan, std::numeric_limits<double>::infinity()}) {
    auto s = Shape::CreateSphere(r);
    ASSERT_FALSE(s);
    EXPECT_NE(s.GetError().message.find("radius"), std::string::npos);
  }
  auto box = Shape::CreateBox({1, -2, 1});
  ASSERT_FALSE(box);
  EXPECT_NE(box.GetError().message.find("half extent y"), std::string::npos);
  EXPECT_FALSE(Shape::CreateBox({1, 1, nan}));
  EXPECT_FALSE(Shape::CreateHull(nullptr));
  EXPECT_FALSE(Shape::CreateSphere(1.0).Value().ComputeMass(0.0));
  EXPECT_FALSE(Shape::CreateBox({1, 1, 1}).Value().ComputeMass(nan));
}

TEST(Shape, BoundingVolumesContainEveryVertexAndSupportIsTheFarthestVertex) {
  std::mt19937_64 rng(21);
  for (int i = 0; i < 200; ++i) {
    const Shape shape = test::RandomPolyhedron(rng);
    const Aabb& box = shape.LocalAabb();
    const Sphere& sphere = shape.LocalBoundingSphere();
    for (const Vec3& v : shape.GetHull().Vertices()) {
      EXPECT_TRUE((v.array() >= box.min.array() - 1e-15).all() &&
                  (v.array() <= box.max.array() + 1e-15).all());
      EXPECT_LE((v - sphere.center).norm(), sphere.radius + 1e-12);
    }
    for (int k = 0; k < 20; ++k) {
      const Vec3 d = test::RandomUnit(rng);
      double best = -1e300;
      for (const Vec3& v : shape.GetHull().Vertices()) best = std::max(best, d.dot(v));
      EXPECT_NEAR(d.dot(shape.Support(d)), best, 1e-12);
    }
  }
}

TEST(Shape, BoxMassPropertiesMatchTheExactPolyhedronIntegral) {
  const Shape box = Shape::CreateBox({0.5, 1.0, 1.5}).Value();
  const MassProperties closed = box.ComputeMass(2.0).Value();
  const MassProperties exact = ComputeMassProperties(box.GetHull(), 2.0).Value();
  EXPECT_NEAR(closed.mass, 2.0 * 6.0, 1e-12);
  EXPECT_NEAR(closed.mass, exact.mass, 1e-12);
  EXPECT_NEAR((closed.inertia - exact.inertia).norm(), 0.0, 1e-12);
  // I_xx = m (2^2 + 3^2) / 12 for full sides 1 x 2 x 3.
  EXPECT_NEAR(closed.inertia(0, 0), 12.0 * 13.0 / 12.0, 1e-12);
}

TEST(Shape, SphereMassPropertiesAreClosedForm) {
  const MassProperties p = Shape::CreateSphere(2.0).Value().ComputeMass(3.0).Value();
  const double mass = 3.0 * 4.0 / 3.0 * std::numbers::pi * 8.0;
  EXPECT_NEAR(p.mass, mass, 1e-12 * mass);
  EXPECT_NEAR(p.inertia(1, 1), 0.4 * mass * 4.0, 1e-12 * mass);
  EXPECT_EQ(p.inertia(0, 1), 0.0);
}

TEST(Shape, HullMassPropertiesComeFromTheHull) {
  const Shape tetra = test::HullShape(test::TetrahedronPoints());
  // The regular tetrahedron inscribed in the cube of side 2 has volume 8/3.
  EXPECT_NEAR(tetra.ComputeMass(1.0).Value().volume, 8.0 / 3.0, 1e-12);
  EXPECT_EQ(tetra.Type(), ShapeType::Hull);
  EXPECT_TRUE(tetra.IsPolyhedron());
}

}  // namespace shape_test
}  // namespace talus
