// CollideShapes, the public pair query: analytic answers for boxes and
// spheres, the same answer as the World's dispatch, the B-towards-A
// convention under swapping, and refusals of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "collision/collide.h"
#include "talus/pair_query.h"

namespace talus {
namespace pair_query_test {

constexpr double kRoundOff = 1e-12;  // metres, unit-sized shapes near the origin

Shape Box(double hx, double hy, double hz) { return Shape::CreateBox(Vec3(hx, hy, hz)).Value(); }

TEST(PairQuery, StackedBoxesGiveTheOverlapAndFourFacePoints) {
  // A 1 m cube resting 0.1 m into a 2 x 1 x 2 m slab below it.
  const Shape top = Box(0.5, 0.5, 0.5);
  const Shape ground = Box(1.0, 0.5, 1.0);
  const PairContact c = CollideShapes(top, {.position = Vec3(0.2, 0.9, -0.1)}, ground, {}).Value();
  ASSERT_TRUE(c.touching);
  EXPECT_NEAR(c.separation, -0.1, kRoundOff);
  EXPECT_NEAR(c.Depth(), 0.1, kRoundOff);
  EXPECT_NEAR((c.normal - Vec3::UnitY()).norm(), 0.0, kRoundOff);  // B (ground) towards A (top)
  ASSERT_EQ(c.pointCount, 4);
  for (int i = 0; i < c.pointCount; ++i) {
    const PairContactPoint& p = c.points[static_cast<std::size_t>(i)];
    EXPECT_NEAR(p.depth, 0.1, kRoundOff);
    EXPECT_NEAR(p.position.y(), 0.45, kRoundOff);  // midway between y = 0.4 and y = 0.5
    EXPECT_NEAR(std::abs(p.position.x() - 0.2), 0.5, kRoundOff);
    EXPECT_NEAR(std::abs(p.position.z() + 0.1), 0.5, kRoundOff);
    // The ground's top face clipped against the cube's vertices: a vertex
    // of A (the cube) on a face of B (the ground).
    EXPECT_EQ(FeatureTypeOf(p.featureId >> 16), PairFeatureType::Vertex);
    EXPECT_EQ(FeatureTypeOf(p.featureId & 0xFFFFu), PairFeatureType::Face);
  }
}

TEST(PairQuery, SeparatedBoxesReportTheGapAndNoPoints) {
  const Shape a = Box(0.5, 0.5, 0.5);
  const PairContact c = CollideShapes(a, {.position = Vec3(0.0, 1.3, 0.0)}, a, {}).Value();
  EXPECT_FALSE(c.touching);
  EXPECT_EQ(c.pointCount, 0);
  EXPECT_NEAR(c.separation, 0.3, kRoundOff);
  EXPECT_NEAR(std::abs(c.normal.y()), 1.0, kRoundOff);
  EXPECT_EQ(c.Depth(), 0.0);
}

TEST(PairQuery, SpheresGiveTheExactGapOrDepth) {
  const Shape s1 = Shape::CreateSphere(0.5).Value();
  const Shape s2 = Shape::CreateSphere(0.25).Value();
  const PairContact apart = CollideShapes(s1, {.position = Vec3(1.0, 0.0, 0.0)}, s2, {}).Value();
  EXPECT_FALSE(apart.touching);
  EXPECT_NEAR(apart.separation, 0.25, kRoundOff);
  EXPECT_NEAR((apart.normal - Vec3::UnitX()).norm(), 0.0, kRoundOff);
  const PairContact deep = CollideShapes(s1, {.position = Vec3(0.0, 0.0, 0.6)}, s2, {}).Value();
  ASSERT_TRUE(deep.touching);
  EXPECT_NEAR(deep.separation, -0.15, kRoundOff);
  ASSERT_EQ(deep.pointCount, 1);
  EXPECT_NEAR(deep.points[0].depth, 0.15, kRoundOff);
}

TEST(PairQuery, SpeculativeMarginGivesNegativeDepths) {
  const Shape a = Box(0.5, 0.5, 0.5);
  NarrowPhaseSettings settings;
  settings.speculativeMargin = 0.05;
  const PairContact c = CollideShapes(a, {.position = Vec3(0.0, 1.02, 0.0)}, a, {}, settings).Value();
  ASSERT_TRUE(c.touching);
  EXPECT_NEAR(c.separation, 0.02, kRoundOff);
  EXPECT_EQ(c.Depth(), 0.0);
  for (int i = 0; i < c.pointCount; ++i)
    EXPECT_NEAR(c.points[static_cast<std::size_t>(i)].depth, -0.02, kRoundOff);
}

TEST(PairQuery, SwappingTheShapesFlipsTheNormalOnly) {
  const Shape box = Box(0.4, 0.3, 0.2);
  const Shape sphere = Shape::CreateSphere(0.3).Value();
  const Transform xfBox{.position = Vec3(0.1, 0.0, 0.0),
                        .rotation = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()))};
  const Transform xfOther{.position = Vec3(0.3, 0.45, 0.1)};
  for (const Shape* other : {&box, &sphere}) {
    const PairContact ab = CollideShapes(box, xfBox, *other, xfOther).Value();
    const PairContact ba = CollideShapes(*other, xfOther, box, xfBox).Value();
    ASSERT_TRUE(ab.touching);
    ASSERT_TRUE(ba.touching);
    EXPECT_NEAR(ab.separation, ba.separation, kRoundOff);
    EXPECT_NEAR((ab.normal + ba.normal).norm(), 0.0, 1e-9);
  }
}

TEST(PairQuery, AnswersAsTheWorldsDispatchDoes) {
  const Shape a = Box(0.5, 0.3, 0.4);
  const Shape b = Box(0.6, 0.2, 0.3);
  const Transform xfA{.position = Vec3(0.0, 0.4, 0.0),
                      .rotation = Quat(Eigen::AngleAxisd(0.3, Vec3(0, 0, 1)))};
  const Transform xfB{.rotation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 0, 0)))};
  const NarrowPhaseSettings settings;
  ContactManifold m{};
  ASSERT_TRUE(Collide(a, xfA, b, xfB, settings, nullptr, nullptr, &m));
  const PairContact c = CollideShapes(a, xfA, b, xfB, settings).Value();
  ASSERT_TRUE(c.touching);
  EXPECT_EQ(c.separation, -m.depth);
  EXPECT_EQ(c.normal, m.normal);
  ASSERT_EQ(c.pointCount, m.pointCount);
  for (int i = 0; i < c.pointCount; ++i) {
    const auto k = static_cast<std::size_t>(i);
    EXPECT_EQ(c.points[k].position, m.points[k].position);
    EXPECT_EQ(c.points[k].depth, m.points[k].depth);
    EXPECT_EQ(c.points[k].featureId, m.points[k].featureId);
  }
}

TEST(PairQuery, RefusesBadInputNamingIt) {
  const Shape a = Box(0.5, 0.5, 0.5);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto notFinite = CollideShapes(a, {.position = Vec3(nan, 0, 0)}, a, {});
  ASSERT_FALSE(notFinite.Ok());
  EXPECT_NE(notFinite.GetError().message.find("xfA.position"), std::string::npos);
  const auto notUnit = CollideShapes(a, {}, a, {.rotation = Quat(2.0, 0.0, 0.0, 0.0)});
  ASSERT_FALSE(notUnit.Ok());
  EXPECT_NE(notUnit.GetError().message.find("xfB.rotation"), std::string::npos);
  NarrowPhaseSettings settings;
  settings.speculativeMargin = -1.0;
  const auto badMargin = CollideShapes(a, {}, a, {}, settings);
  ASSERT_FALSE(badMargin.Ok());
  EXPECT_NE(badMargin.GetError().message.find("speculativeMargin"), std::string::npos);
}

}  // namespace pair_query_test
}  // namespace talus
