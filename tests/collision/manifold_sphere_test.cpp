// Sphere contacts: known answers on a face, an edge and a vertex of a box,
// through both the box fast path and the general hull routine; the centre
// inside (deepest face); sphere-sphere; and the swap rule. Tolerance 1e-12
// m: each answer is a handful of exact operations on numbers of order 1.
#include <gtest/gtest.h>

#include <cmath>

#include "collision/collide.h"
#include "collision/sat_test_fixtures.h"

namespace talus {
namespace manifold_sphere_test {

constexpr double kExact = 1e-12;
constexpr double kRadius = 0.5;
constexpr double kDepth = 0.01;

Transform At(const Vec3& p) { return {.position = p, .rotation = Quat::Identity()}; }

ContactManifold MustCollide(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB) {
  ContactManifold m{};
  EXPECT_TRUE(Collide(a, xfA, b, xfB, {}, nullptr, nullptr, &m));
  return m;
}

// The unit box as a Box shape and as a general Hull shape.
class BoxKinds : public ::testing::TestWithParam<bool> {
 protected:
  Shape Box() const {
    return GetParam() ? test::BoxShape({0.5, 0.5, 0.5}) : test::HullShape(test::BoxPoints({0.5, 0.5, 0.5}));
  }
};

TEST_P(BoxKinds, SphereOnAFaceEdgeOrVertexTouchesThatFeature) {
  const Shape sphere = Shape::CreateSphere(kRadius).Value();
  const Shape box = Box();
  const Vec3 features[] = {{0.1, 0.5, -0.2}, {0.5, 0.5, 0.1}, {0.5, 0.5, 0.5}};
  const Vec3 directions[] = {Vec3::UnitY(), Vec3(1, 1, 0).normalized(), Vec3(1, 1, 1).normalized()};
  for (int i = 0; i < 3; ++i) {
    const Vec3 centre = features[i] + directions[i] * (kRadius - kDepth);
    const ContactManifold m = MustCollide(sphere, At(centre), box, At({0, 0, 0}));
    EXPECT_NEAR((m.normal - directions[i]).norm(), 0.0, kExact) << i;
    EXPECT_NEAR(m.depth, kDepth, kExact) << i;
    ASSERT_EQ(m.pointCount, 1);
    EXPECT_NEAR((m.points[0].position - (features[i] - directions[i] * kDepth / 2)).norm(), 0.0, kExact) << i;
  }
}

TEST_P(BoxKinds, SphereCentreInsideLeavesThroughTheNearestFace) {
  const Shape sphere = Shape::CreateSphere(kRadius).Value();
  const ContactManifold m = MustCollide(sphere, At({0.1, 0.0, 0.4}), Box(), At({0, 0, 0}));
  EXPECT_NEAR((m.normal - Vec3::UnitZ()).norm(), 0.0, kExact);
  EXPECT_NEAR(m.depth, kRadius + 0.1, kExact);
  EXPECT_NEAR((m.points[0].position - Vec3(0.1, 0.0, 0.5 - (kRadius + 0.1) / 2)).norm(), 0.0, kExact);
}

TEST_P(BoxKinds, SphereJustOutOfReachDoesNotTouch) {
  const Shape sphere = Shape::CreateSphere(kRadius).Value();
  ContactManifold m{};
  const Vec3 corner(0.5, 0.5, 0.5);
  EXPECT_FALSE(Collide(sphere, At(corner + Vec3(1, 1, 1).normalized() * (kRadius + 1e-6)), Box(),
                       At({0, 0, 0}), {}, nullptr, nullptr, &m));
  // ...but does within a speculative margin, with a negative depth.
  EXPECT_TRUE(Collide(sphere, At(corner + Vec3(1, 1, 1).normalized() * (kRadius + 1e-6)), Box(),
                      At({0, 0, 0}), {.speculativeMargin = 1e-3}, nullptr, nullptr, &m));
  EXPECT_NEAR(m.depth, -1e-6, kExact);
}

INSTANTIATE_TEST_SUITE_P(Sphere, BoxKinds, ::testing::Values(true, false));

TEST(Sphere, BoxFastPathAgreesWithHullRoutineOnRandomPlacements) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coordinate(-1.2, 1.2);
  const Shape sphere = Shape::CreateSphere(0.3).Value();
  const Shape box = test::BoxShape({0.5, 0.7, 0.4});
  const Shape hull = test::HullShape(test::BoxPoints({0.5, 0.7, 0.4}));
  int touching = 0;
  for (int i = 0; i < 3000; ++i) {
    const Transform xfS = At({coordinate(rng), coordinate(rng), coordinate(rng)});
    const Transform xfB{.position = Vec3::Zero(), .rotation = test::RandomRotation(rng)};
    ContactManifold fast{};
    ContactManifold general{};
    const bool hitFast = Collide(sphere, xfS, box, xfB, {}, nullptr, nullptr, &fast);
    ASSERT_EQ(hitFast, Collide(sphere, xfS, hull, xfB, {}, nullptr, nullptr, &general));
    if (!hitFast) continue;
    ++touching;
    EXPECT_NEAR(fast.depth, general.depth, 1e-12);
    EXPECT_NEAR((fast.normal - general.normal).norm(), 0.0, 1e-9);
    EXPECT_NEAR((fast.points[0].position - general.points[0].position).norm(), 0.0, 1e-12);
  }
  EXPECT_GT(touching, 500);
}

TEST(Sphere, SphereSphereTouchesAlongTheCentreLine) {
  const Shape a = Shape::CreateSphere(0.5).Value();
  const Shape b = Shape::CreateSphere(1.0).Value();
  const Vec3 direction = Vec3(1, 2, 2) / 3.0;
  const ContactManifold m = MustCollide(a, At(direction * 1.4), b, At({0, 0, 0}));
  EXPECT_NEAR((m.normal - direction).norm(), 0.0, kExact);
  EXPECT_NEAR(m.depth, 0.1, kExact);
  EXPECT_NEAR((m.points[0].position - direction * 0.95).norm(), 0.0, kExact);
}

TEST(Sphere, SwappingSphereAndPolyhedronFlipsOnlyTheNormal) {
  std::mt19937_64 rng(12);
  const Shape sphere = Shape::CreateSphere(0.4).Value();
  for (int i = 0; i < 500; ++i) {
    const Shape poly = test::RandomPolyhedron(rng);
    const Transform xfS = At(test::RandomUnit(rng) * 1.0);
    const Transform xfP{.position = Vec3::Zero(), .rotation = test::RandomRotation(rng)};
    ContactManifold ab{};
    ContactManifold ba{};
    const bool hit = Collide(sphere, xfS, poly, xfP, {}, nullptr, nullptr, &ab);
    ASSERT_EQ(hit, Collide(poly, xfP, sphere, xfS, {}, nullptr, nullptr, &ba));
    if (!hit) continue;
    EXPECT_EQ(ab.normal, Vec3(-ba.normal));
    EXPECT_EQ(ab.depth, ba.depth);
    EXPECT_EQ(ab.points[0].position, ba.points[0].position);
    EXPECT_EQ(ab.points[0].featureId, SwapFeatureId(ba.points[0].featureId));
  }
}

}  // namespace manifold_sphere_test
}  // namespace talus
