// GetContactPoints: what the testbed reads back from a World through the
// public API. A box resting on a ground box must report the four corners
// of its bottom face, with the normal from B towards A and small depths.
#include <gtest/gtest.h>

#include <cmath>

#include "talus/world.h"

namespace talus {
namespace contact_query_test {

TEST(ContactQuery, RestingBoxReportsItsFourBottomCornersWithNormalFromBToA) {
  World world;
  auto ground = world.CreateBody({.type = BodyType::Static,
                                  .position = Vec3(0, -0.5, 0),
                                  .shape = Shape::CreateBox(Vec3(5, 0.5, 5)).Value()});
  auto box = world.CreateBody({.type = BodyType::Dynamic,
                               .position = Vec3(0, 0.499, 0),
                               .shape = Shape::CreateBox(Vec3(0.5, 0.5, 0.5)).Value(),
                               .friction = 0.3});
  ASSERT_TRUE(ground && box);
  EXPECT_TRUE(world.GetContactPoints().empty()) << "no step yet";
  ASSERT_TRUE(world.Step(1.0 / 60.0));
  const auto points = world.GetContactPoints();
  ASSERT_EQ(points.size(), 4u);
  for (const ContactPointInfo& point : points) {
    ASSERT_TRUE(world.IsValid(point.bodyA) && world.IsValid(point.bodyB));
    // The normal points towards A, whichever body A is.
    const double up = point.bodyA == box.Value() ? 1.0 : -1.0;
    EXPECT_NEAR(point.normal.y(), up, 1e-9);
    // Placed 1 mm deep, then one step of gravity and Baumgarte: under 2 mm.
    EXPECT_GT(point.depth, 0.0);
    EXPECT_LT(point.depth, 0.002);
    EXPECT_NEAR(std::abs(point.position.x()), 0.5, 1e-6);
    EXPECT_NEAR(std::abs(point.position.z()), 0.5, 1e-6);
    EXPECT_DOUBLE_EQ(point.friction, std::sqrt(0.3 * 0.5));  // geometric mean with the ground's default 0.5
  }
}

}  // namespace contact_query_test
}  // namespace talus
