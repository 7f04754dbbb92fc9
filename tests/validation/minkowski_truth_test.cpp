// The truth itself: the Minkowski-difference answer against the closed form
// for boxes sharing a rotation, its sign conventions, and the libccd
// wrapper's support mapping against brute force.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sat_check.h"
#include "talus/reference/ccd_oracle.h"
#include "talus/reference/minkowski_truth.h"

namespace talus {
namespace minkowski_truth_test {

using reference::ComputePenetrationTruth;

Quat RandomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  return Quat(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
}

TEST(MinkowskiTruth, AgreesWithClosedFormForBoxesSharingARotation) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> extent(0.05, 2.0);
  std::uniform_real_distribution<double> offset(-3.0, 3.0);
  for (int i = 0; i < 150; ++i) {
    const Vec3 halfA(extent(rng), extent(rng), extent(rng));
    const Vec3 halfB(extent(rng), extent(rng), extent(rng));
    const Quat rotation = RandomRotation(rng);
    const Vec3 localOffset(offset(rng), offset(rng), offset(rng));
    const Transform xfA{.position = Vec3(0.3, -0.2, 0.1), .rotation = rotation};
    const Transform xfB{.position = xfA.position + rotation * localOffset, .rotation = rotation};
    const auto truth =
        ComputePenetrationTruth(Hull::Box(halfA).Value(), xfA, Hull::Box(halfB).Value(), xfB).Value();
    const double closed = validation::BoxPairSignedDistance(halfA, halfB, localOffset);
    // Round-off of rotating metre-sized coordinates: 1e-12 m.
    EXPECT_NEAR(truth.signedDistance, closed, 1e-12) << "case " << i;
    EXPECT_EQ(truth.intersecting, closed <= 0.0) << "case " << i;
  }
}

TEST(MinkowskiTruth, NormalPointsFromBTowardsAAndDepthIsPositive) {
  const Hull box = Hull::Box(Vec3(1, 1, 1)).Value();
  // B overlaps A by 0.25 m from the +x side: A must move along -x.
  const auto truth = ComputePenetrationTruth(box, {}, box, {.position = Vec3(1.75, 0.1, 0.0)}).Value();
  EXPECT_TRUE(truth.intersecting);
  EXPECT_NEAR(truth.Depth(), 0.25, 1e-14);
  EXPECT_NEAR(truth.normal.x(), -1.0, 1e-14);
  // Separated by 0.5 m along +y: gap 0.5, normal from B (above) to A is -y.
  const auto apart = ComputePenetrationTruth(box, {}, box, {.position = Vec3(0.0, 2.5, 0.3)}).Value();
  EXPECT_FALSE(apart.intersecting);
  EXPECT_NEAR(apart.signedDistance, 0.5, 1e-14);
  EXPECT_NEAR(apart.normal.y(), -1.0, 1e-14);
}

TEST(MinkowskiTruth, SeparatedBoxesCornerToCornerGiveEuclideanGap) {
  const Hull box = Hull::Box(Vec3(0.5, 0.5, 0.5)).Value();
  const auto truth = ComputePenetrationTruth(box, {}, box, {.position = Vec3(2, 2, 2)}).Value();
  EXPECT_NEAR(truth.signedDistance, std::sqrt(3.0), 1e-14);
}

TEST(MinkowskiTruth, BuiltDifferenceMatchesQhull) {
  std::mt19937_64 rng(11);
  const Hull box = Hull::Box(Vec3(0.7, 0.3, 0.2)).Value();
  for (int i = 0; i < 20; ++i) {
    const Transform xfA{.position = Vec3::Zero(), .rotation = RandomRotation(rng)};
    const Transform xfB{.position = Vec3(0.5, 0.1, -0.2), .rotation = RandomRotation(rng)};
    const auto check = reference::CheckMinkowskiWithQhull(box, xfA, box, xfB);
    EXPECT_TRUE(check.Ok()) << (check.Ok() ? "" : check.GetError().message);
  }
}

TEST(CcdOracle, SupportIsTheFarthestWorldVertex) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Hull box = Hull::Box(Vec3(0.4, 1.0, 0.1)).Value();
  const reference::CcdObject object{
      .hull = &box, .transform = {.position = Vec3(1, 2, 3), .rotation = RandomRotation(rng)}};
  for (int i = 0; i < 200; ++i) {
    const Vec3 d(normal(rng), normal(rng), normal(rng));
    double best = -1e300;
    for (const Vec3& v : box.Vertices()) best = std::max(best, d.dot(object.transform.Apply(v)));
    EXPECT_NEAR(d.dot(object.Support(d)), best, 1e-12);
  }
  EXPECT_NEAR((object.Center() - Vec3(1, 2, 3)).norm(), 0.0, 1e-12);
}

TEST(CcdOracle, GjkPenetrationOfOverlappingBoxesMatchesTruth) {
  const Hull box = Hull::Box(Vec3(1, 1, 1)).Value();
  const reference::CcdObject a{.hull = &box, .transform = {}};
  const reference::CcdObject b{.hull = &box, .transform = {.position = Vec3(0.1, 1.8, 0.2)}};
  const auto answer = reference::CcdGjkPenetration(a, b);
  ASSERT_EQ(answer.status, reference::CcdStatus::Ok);
  EXPECT_TRUE(answer.intersecting);
  // EPA tolerance 1e-6 m (CcdSettings).
  EXPECT_NEAR(answer.depth, 0.2, 1e-6);
  EXPECT_NEAR(answer.normal.y(), -1.0, 1e-6);
  EXPECT_FALSE(
      reference::CcdGjkIntersect(a, {.hull = &box, .transform = {.position = Vec3(0, 2.5, 0)}}).intersecting);
}

}  // namespace minkowski_truth_test
}  // namespace talus
