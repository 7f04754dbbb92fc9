// Known answers for polyhedron contacts: the write-up's figures 3 and 4 and
// the classic resting configurations, each with an exact depth, normal and
// point set. Tolerance 1e-12 m: every answer here is a few exact
// operations on numbers of order 1, so only round-off separates them.
#include <gtest/gtest.h>

#include <cmath>

#include "collision/collide.h"
#include "collision/sat_test_fixtures.h"

namespace talus {
namespace manifold_known_test {

constexpr double kExact = 1e-12;

ContactManifold MustCollide(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                            ManifoldMode mode, SatMode satMode = SatMode::GaussMapPruned) {
  ContactManifold m{};
  const NarrowPhaseSettings settings{.satMode = satMode, .manifoldMode = mode};
  EXPECT_TRUE(Collide(a, xfA, b, xfB, settings, nullptr, nullptr, &m));
  return m;
}

bool HasPointNear(const ContactManifold& m, const Vec3& p, double tolerance) {
  for (int i = 0; i < m.pointCount; ++i) {
    if ((m.points[static_cast<std::size_t>(i)].position - p).norm() <= tolerance) return true;
  }
  return false;
}

Transform At(const Vec3& p, const Quat& q = Quat::Identity()) { return {.position = p, .rotation = q}; }

class BothGenerators : public ::testing::TestWithParam<ManifoldMode> {};

TEST_P(BothGenerators, BoxRestingFaceToFaceOnBoxHasFourPointsAtExactDepth) {
  const double depth = 0.01;
  const Shape top = test::BoxShape({0.5, 0.5, 0.5});
  const Shape ground = test::BoxShape({2, 0.5, 2});
  const ContactManifold m = MustCollide(top, At({0.2, 1.0 - depth, -0.1}), ground, At({0, 0, 0}), GetParam());
  EXPECT_NEAR((m.normal - Vec3::UnitY()).norm(), 0.0, kExact);
  EXPECT_NEAR(m.depth, depth, kExact);
  ASSERT_EQ(m.pointCount, 4);
  for (double x : {-0.3, 0.7}) {
    for (double z : {-0.6, 0.4})
      EXPECT_TRUE(HasPointNear(m, {x, 0.5 - depth / 2, z}, kExact)) << x << " " << z;
  }
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(m.points[static_cast<std::size_t>(i)].depth, depth, kExact);
}

TEST_P(BothGenerators, TetrahedronOnBoxOnGroundGivesTwoFaceManifolds) {
  // The write-up's figure 3: a box on the ground, a tetrahedron lying on the
  // box with one face down. Depths 0.02 and 0.03.
  const Shape ground = test::BoxShape({5, 0.5, 5});
  const Shape box = test::BoxShape({1, 0.5, 1});
  const Shape tetra = test::HullShape({{-0.5, 0, -0.4}, {0.5, 0, -0.4}, {0, 0, 0.5}, {0, 0.8, 0}});
  const ContactManifold onGround = MustCollide(box, At({0, 0.98, 0}), ground, At({0, 0, 0}), GetParam());
  EXPECT_NEAR(onGround.depth, 0.02, kExact);
  EXPECT_EQ(onGround.pointCount, 4);
  const ContactManifold onBox = MustCollide(tetra, At({0.1, 1.45, 0}), box, At({0, 0.98, 0}), GetParam());
  EXPECT_NEAR((onBox.normal - Vec3::UnitY()).norm(), 0.0, kExact);
  EXPECT_NEAR(onBox.depth, 0.03, kExact);
  ASSERT_EQ(onBox.pointCount, 3);
  // Each point lies on the vertical through a tetrahedron corner. Midway
  // (y = 1.465) would be outside the tetrahedron, whose sides lean in over
  // its corners; the only height on that line inside both shapes is the
  // corner itself (y = 1.45), where the points go.
  for (const Vec3& corner : {Vec3(-0.4, 0, -0.4), Vec3(0.6, 0, -0.4), Vec3(0.1, 0, 0.5)}) {
    EXPECT_TRUE(HasPointNear(onBox, corner + Vec3(0, 1.45, 0), kExact)) << corner.transpose();
  }
}

TEST_P(BothGenerators, BoxBalancedOnItsEdgeTouchesAlongTheEdge) {
  const double depth = 0.01;
  const Shape box = test::BoxShape({0.5, 0.5, 0.5});
  const Shape ground = test::BoxShape({3, 0.5, 3});
  const Quat tilt(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitZ()));
  const ContactManifold m =
      MustCollide(box, At({0, 0.5 + std::sqrt(0.5) - depth, 0}, tilt), ground, At({0, 0, 0}), GetParam());
  EXPECT_NEAR((m.normal - Vec3::UnitY()).norm(), 0.0, kExact);
  EXPECT_NEAR(m.depth, depth, kExact);
  if (GetParam() == ManifoldMode::Clipped) {
    ASSERT_EQ(m.pointCount, 2);
    EXPECT_TRUE(HasPointNear(m, {0, 0.5 - depth / 2, 0.5}, kExact));
    EXPECT_TRUE(HasPointNear(m, {0, 0.5 - depth / 2, -0.5}, kExact));
  } else {
    // The write-up's rule: the box's two edge corners (ground vertices are
    // not inside the box).
    ASSERT_EQ(m.pointCount, 2);
    EXPECT_TRUE(HasPointNear(m, {0, 0.5 - depth / 2, 0.5}, kExact));
  }
}

TEST_P(BothGenerators, CrossedEdgesTouchAtOnePointAtTheCrossing) {
  const double depth = 0.01;
  const Shape box = test::BoxShape({0.5, 0.5, 0.5});
  const Quat aboutZ(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitZ()));
  const Quat aboutX(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitX()));
  const double h = std::sqrt(0.5);
  for (SatMode satMode : {SatMode::Full, SatMode::GaussMapPruned}) {
    const ContactManifold m =
        MustCollide(box, At({0, 2 * h - depth, 0}, aboutZ), box, At({0, 0, 0}, aboutX), GetParam(), satMode);
    EXPECT_NEAR((m.normal - Vec3::UnitY()).norm(), 0.0, kExact);
    EXPECT_NEAR(m.depth, depth, kExact);
    ASSERT_EQ(m.pointCount, 1);
    EXPECT_NEAR((m.points[0].position - Vec3(0, h - depth / 2, 0)).norm(), 0.0, kExact);
  }
}

TEST_P(BothGenerators, TetrahedraEdgeToEdgeTouchAtTheEdgesClosestPoints) {
  // The write-up's figure 4: A's lowest edge runs along z, B's highest along
  // x; they overlap by 0.02 and cross at x = 0.3, z = -0.2.
  const double depth = 0.02;
  const Shape a = test::HullShape({{0, 0, -1}, {0, 0, 1}, {1, 1.5, 0}, {-1, 1.5, 0}});
  const Shape b = test::HullShape({{-1, 0, 0}, {1, 0, 0}, {0, -1.5, 1}, {0, -1.5, -1}});
  const ContactManifold m = MustCollide(a, At({0.3, -depth, 0}), b, At({0, 0, -0.2}), GetParam());
  EXPECT_NEAR((m.normal - Vec3::UnitY()).norm(), 0.0, kExact);
  EXPECT_NEAR(m.depth, depth, kExact);
  ASSERT_EQ(m.pointCount, 1);
  EXPECT_NEAR((m.points[0].position - Vec3(0.3, -depth / 2, -0.2)).norm(), 0.0, kExact);
}

INSTANTIATE_TEST_SUITE_P(Manifold, BothGenerators,
                         ::testing::Values(ManifoldMode::WriteUp, ManifoldMode::Clipped));

TEST(Manifold, ClippedPointsCarryTheirOwnDepthWhenTilted) {
  // A box tilted slightly about z on the ground: the clipped points keep
  // their individual depths (the lowest corner deepest), WriteUp gives all
  // the manifold depth.
  const Shape box = test::BoxShape({0.5, 0.5, 0.5});
  const Shape ground = test::BoxShape({3, 0.5, 3});
  const double angle = 0.004;
  const Quat tilt(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
  const double lowest = 0.5 * (std::cos(angle) + std::sin(angle));
  const double depth = 0.005;
  const ContactManifold m =
      MustCollide(box, At({0, 0.5 + lowest - depth, 0}, tilt), ground, At({0, 0, 0}), ManifoldMode::Clipped);
  EXPECT_NEAR(m.depth, depth, 1e-12);
  ASSERT_EQ(m.pointCount, 4);
  double deepest = 0.0;
  double shallowest = 1.0;
  for (int i = 0; i < 4; ++i) {
    deepest = std::max(deepest, m.points[static_cast<std::size_t>(i)].depth);
    shallowest = std::min(shallowest, m.points[static_cast<std::size_t>(i)].depth);
  }
  EXPECT_NEAR(deepest, depth, 1e-12);
  EXPECT_NEAR(shallowest, depth - std::sin(angle), 1e-12);
}

TEST(Manifold, ClippedFeatureIdsAreStableUnderSmallMotion) {
  const Shape box = test::BoxShape({0.5, 0.5, 0.5});
  const Shape ground = test::BoxShape({3, 0.5, 3});
  const ContactManifold m1 = MustCollide(box, At({0, 0.99, 0}), ground, At({0, 0, 0}), ManifoldMode::Clipped);
  const ContactManifold m2 =
      MustCollide(box, At({0.01, 0.985, 0.003}), ground, At({0, 0, 0}), ManifoldMode::Clipped);
  ASSERT_EQ(m1.pointCount, m2.pointCount);
  for (int i = 0; i < m1.pointCount; ++i) {
    const auto& p = m1.points[static_cast<std::size_t>(i)];
    bool matched = false;
    for (int j = 0; j < m2.pointCount; ++j) {
      const auto& q = m2.points[static_cast<std::size_t>(j)];
      if (q.featureId == p.featureId) matched = (q.position - p.position).norm() < 0.02;
    }
    EXPECT_TRUE(matched) << "point " << i;
  }
  for (int i = 0; i < m1.pointCount; ++i) {
    for (int j = 0; j < i; ++j)
      EXPECT_NE(m1.points[static_cast<std::size_t>(i)].featureId,
                m1.points[static_cast<std::size_t>(j)].featureId);
  }
}

}  // namespace manifold_known_test
}  // namespace talus
