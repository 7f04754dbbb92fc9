// Resting faces of hulls: known shapes, an unstable face, and over random
// point clouds the heights against the support distance of the points and
// the theorem that every convex body has a stable face.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "talus/harness/analytic/hull_rest_analysis.h"

namespace talus::harness {
namespace hull_rest_test {

std::vector<Vec3> BoxPoints(const Vec3& half, const Vec3& offset) {
  std::vector<Vec3> points;
  for (int i = 0; i < 8; ++i) {
    points.push_back(offset + Vec3(i & 1 ? half.x() : -half.x(), i & 2 ? half.y() : -half.y(),
                                   i & 4 ? half.z() : -half.z()));
  }
  return points;
}

TEST(HullRest, BoxRestsStablyOnEveryFaceAtItsHalfExtent) {
  const Vec3 half(0.5, 0.25, 0.125);
  auto analysis = AnalyseHullRest(BoxPoints(half, Vec3(3, -2, 1)));
  ASSERT_TRUE(analysis) << analysis.GetError().message;
  EXPECT_LT((analysis.Value().centroid - Vec3(3, -2, 1)).norm(), 1e-12);
  ASSERT_EQ(analysis.Value().faces.size(), 6u);
  for (const HullRestFace& face : analysis.Value().faces) {
    EXPECT_TRUE(face.stable);
    const Vec3 n = face.normal.cwiseAbs();
    // Exact to round-off of coordinates ~3.
    EXPECT_NEAR(face.height, n.dot(half), 1e-12);
  }
  const int down = analysis.Value().NearestFace(Vec3(0.1, -1, 0));
  EXPECT_NEAR(analysis.Value().faces[down].normal.y(), -1.0, 1e-12);
}

TEST(HullRest, ObtusePrismHasAnUnstableSlantedFace) {
  // Cross-section (0,0), (3,0), (4,1) extruded along z: centroid (7/3, 1/3).
  // On the face through (3,0)-(4,1) the centroid projects 1/6 of the edge
  // length beyond (3,0): the body would roll onto its bottom face.
  std::vector<Vec3> points;
  for (const double z : {-0.5, 0.5}) {
    points.push_back(Vec3(0, 0, z));
    points.push_back(Vec3(3, 0, z));
    points.push_back(Vec3(4, 1, z));
  }
  auto analysis = AnalyseHullRest(points);
  ASSERT_TRUE(analysis) << analysis.GetError().message;
  EXPECT_LT((analysis.Value().centroid - Vec3(7.0 / 3.0, 1.0 / 3.0, 0)).norm(), 1e-12);
  const HullRestFace& bottom = analysis.Value().faces[analysis.Value().NearestFace(Vec3(0, -1, 0))];
  EXPECT_TRUE(bottom.stable);
  EXPECT_NEAR(bottom.height, 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(bottom.margin, std::min({7.0 / 3.0, 3.0 - 7.0 / 3.0, 0.5}), 1e-12);
  const HullRestFace& slant = analysis.Value().faces[analysis.Value().NearestFace(Vec3(1, -1, 0))];
  EXPECT_FALSE(slant.stable);
  EXPECT_NEAR(slant.margin, -std::sqrt(2.0) / 6.0, 1e-12);
}

TEST(HullRest, RandomHullsHaveSupportHeightsAndAStableFace) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Vec3> points(6 + trial % 30);
    const Vec3 scale(0.2 + (trial % 7) * 0.3, 1.0, 0.5 + (trial % 3));
    for (Vec3& p : points) {
      p = Vec3(coordinate(random), coordinate(random), coordinate(random)).cwiseProduct(scale);
    }
    auto analysis = AnalyseHullRest(points);
    ASSERT_TRUE(analysis) << analysis.GetError().message;
    int stable = 0;
    for (const HullRestFace& face : analysis.Value().faces) {
      // The face's plane touches the hull: its distance from the centroid
      // is the largest of the points' along its normal (the support).
      double support = -1e9;
      for (const Vec3& p : points)
        support = std::max(support, face.normal.dot(p - analysis.Value().centroid));
      // The hull builder's tolerance (~1e-10 here) bounds how far a vertex
      // may stick out of a merged face.
      ASSERT_NEAR(face.height, support, 1e-9) << "trial " << trial;
      EXPECT_GT(face.height, 0.0);
      stable += face.stable ? 1 : 0;
    }
    // A convex body always has a face it can rest on (the one nearest the centroid).
    EXPECT_GE(stable, 1) << "trial " << trial;
    const auto nearest =
        std::min_element(analysis.Value().faces.begin(), analysis.Value().faces.end(),
                         [](const HullRestFace& a, const HullRestFace& b) { return a.height < b.height; });
    EXPECT_TRUE(nearest->stable) << "trial " << trial;
  }
}

TEST(HullRest, FlatPointSetsAreRefused) {
  const std::vector<Vec3> flat = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 1)};
  EXPECT_FALSE(AnalyseHullRest(flat));
}

}  // namespace hull_rest_test
}  // namespace talus::harness
