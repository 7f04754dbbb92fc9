// BuildHull: known shapes, bad input, the vertex cap, determinism, and the
// documented invariants on many random and adversarial point sets.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "geometry/hull_check.h"
#include "talus/hull_builder.h"

namespace talus {
namespace hull_builder_test {

using test::CheckHull;

std::string ErrorOf(const std::vector<Vec3>& points, const HullBuildSettings& settings = {}) {
  auto hull = BuildHull(points, settings);
  return hull ? std::string("(no error)") : hull.GetError().message;
}

TEST(HullBuilder, CubeWithFaceAndEdgePointsHasEightVerticesSixQuadFaces) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const auto points = test::CubeWithSurfacePoints(seed, 300);
    auto hull = BuildHull(points);
    ASSERT_TRUE(hull) << hull.GetError().message;
    EXPECT_EQ(hull.Value().VertexCount(), 8);
    EXPECT_EQ(hull.Value().FaceCount(), 6);
    for (int f = 0; f < 6; ++f) EXPECT_EQ(hull.Value().FaceVertices(f).size(), 4u);
    // The corners are exact in binary, so the volume is 8 up to rounding.
    EXPECT_NEAR(test::HullVolume(hull.Value()), 8.0, 1e-12);
    EXPECT_TRUE(CheckHull(hull.Value(), points));
  }
}

TEST(HullBuilder, OctahedronHasSixVerticesEightTriangles) {
  std::vector<Vec3> points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, 0, 0}};
  auto hull = BuildHull(points);
  ASSERT_TRUE(hull) << hull.GetError().message;
  EXPECT_EQ(hull.Value().VertexCount(), 6);
  EXPECT_EQ(hull.Value().FaceCount(), 8);
  EXPECT_EQ(hull.Value().EdgeCount(), 12);
  EXPECT_NEAR(test::HullVolume(hull.Value()), 4.0 / 3.0, 1e-14);  // two pyramids of base 2, height 1
  EXPECT_TRUE(CheckHull(hull.Value(), points));
}

TEST(HullBuilder, PointsOnSphereAreAllVerticesAndVolumeApproachesBall) {
  const auto points = test::SpherePoints(7, 2000);
  auto hull = BuildHull(points);
  ASSERT_TRUE(hull) << hull.GetError().message;
  EXPECT_EQ(hull.Value().VertexCount(), 2000);
  EXPECT_EQ(hull.Value().FaceCount(), 2 * 2000 - 4);  // general position: all triangles
  const double volume = test::HullVolume(hull.Value());
  // An inscribed polytope of 2000 random vertices misses about 1% of the ball.
  EXPECT_LT(volume, 4.0 / 3.0 * std::numbers::pi);
  EXPECT_GT(volume, 0.98 * 4.0 / 3.0 * std::numbers::pi);
  EXPECT_TRUE(CheckHull(hull.Value(), points));
}

TEST(HullBuilder, RejectsSetsWithoutVolume) {
  EXPECT_NE(ErrorOf({}).find("at least 4 points, got 0"), std::string::npos);
  EXPECT_NE(ErrorOf({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}).find("at least 4 points, got 3"), std::string::npos);
  EXPECT_NE(ErrorOf({{1, 2, 3}, {1, 2, 3}, {1, 2, 3}, {1, 2, 3}, {1, 2, 3}}).find("coincide"),
            std::string::npos);
  std::vector<Vec3> threeRepeated;
  for (int i = 0; i < 10; ++i) threeRepeated.push_back(i % 3 == 0 ? Vec3(0, 0, 0) : Vec3(i % 3, 1, 0));
  EXPECT_NE(ErrorOf(threeRepeated).find("coplanar"), std::string::npos);
  std::vector<Vec3> line;
  for (int i = 0; i < 50; ++i) line.push_back(Vec3(1, 2, 3) * (0.1 * i));
  EXPECT_NE(ErrorOf(line).find("collinear"), std::string::npos);
  std::vector<Vec3> plane;
  for (const Vec3& p : test::BallPoints(3, 200)) plane.push_back({p.x(), p.y(), 0.5 * p.x() - p.y()});
  EXPECT_NE(ErrorOf(plane).find("coplanar"), std::string::npos);
}

TEST(HullBuilder, RejectsNanAndInfNamingThePoint) {
  auto points = test::BallPoints(5, 100);
  points[17].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(ErrorOf(points), "point 17: coordinate y is NaN");
  points = test::BallPoints(5, 100);
  points[42].z() = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(ErrorOf(points), "point 42: coordinate z is infinite");
}

TEST(HullBuilder, RejectsBadSettings) {
  const auto points = test::BallPoints(5, 100);
  EXPECT_NE(ErrorOf(points, {.maxVertices = 3}).find("maxVertices"), std::string::npos);
  EXPECT_NE(ErrorOf(points, {.maxVertices = -1}).find("maxVertices"), std::string::npos);
  EXPECT_NE(ErrorOf(points, {.tolerance = -1.0}).find("tolerance"), std::string::npos);
  EXPECT_NE(ErrorOf(points, {.tolerance = std::numeric_limits<double>::quiet_NaN()}).find("tolerance"),
            std::string::npos);
}

TEST(HullBuilder, VertexCapLimitsVertexCountAndKeepsHullValid) {
  const auto points = test::SpherePoints(11, 3000);
  for (int cap : {4, 5, 8, 20, 100, 1000}) {
    auto hull = BuildHull(points, {.maxVertices = cap});
    ASSERT_TRUE(hull) << hull.GetError().message;
    EXPECT_LE(hull.Value().VertexCount(), cap);
    EXPECT_GE(hull.Value().VertexCount(), std::min(cap, 4));
    // The capped hull holds only its own vertices, not all input points.
    std::vector<Vec3> own(hull.Value().Vertices().begin(), hull.Value().Vertices().end());
    EXPECT_TRUE(CheckHull(hull.Value(), own));
  }
  // A cap the hull never reaches changes nothing.
  auto capped = BuildHull(points, {.maxVertices = 5000});
  ASSERT_TRUE(capped);
  EXPECT_EQ(capped.Value().VertexCount(), 3000);
}

TEST(HullBuilder, BuildingTwiceGivesIdenticalHulls) {
  for (const auto& points : {test::BallPoints(21, 5000), test::CubeWithSurfacePoints(21, 500)}) {
    const Hull a = BuildHull(points).Value();
    const Hull b = BuildHull(points).Value();
    ASSERT_EQ(a.VertexCount(), b.VertexCount());
    ASSERT_EQ(a.HalfEdgeCount(), b.HalfEdgeCount());
    for (int v = 0; v < a.VertexCount(); ++v) {
      EXPECT_EQ(a.Vertices()[static_cast<std::size_t>(v)], b.Vertices()[static_cast<std::size_t>(v)]);
    }
    for (int h = 0; h < a.HalfEdgeCount(); ++h) {
      const auto& x = a.HalfEdges()[static_cast<std::size_t>(h)];
      const auto& y = b.HalfEdges()[static_cast<std::size_t>(h)];
      EXPECT_TRUE(x.origin == y.origin && x.twin == y.twin && x.next == y.next && x.face == y.face);
    }
  }
}

// Thousands of small random sets of every awkward kind; every one must build
// and satisfy every invariant.
TEST(HullBuilder, InvariantsHoldOnManyRandomAndAdversarialSets) {
  std::mt19937_64 rng(12345);
  std::uniform_int_distribution<int> sizes(4, 120);
  int built = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int n = sizes(rng);
    const auto seed = static_cast<std::uint64_t>(trial);
    std::vector<Vec3> points;
    switch (trial % 6) {
      case 0:
        points = test::BallPoints(seed, n);
        break;
      case 1:
        points = test::SpherePoints(seed, n);
        break;
      case 2:
        points = test::CubeWithSurfacePoints(seed, n);
        break;
      case 3:  // large offset: near 1e4, spread 1
        points = test::BallPoints(seed, n, Vec3(1e4, -1e4, 1e4), 1.0);
        break;
      case 4: {  // nearly flat sliver, 1e-6 thick, with duplicates
        for (const Vec3& p : test::BallPoints(seed, n)) points.push_back({p.x(), p.y(), 1e-6 * p.z()});
        for (int i = 0; i < n / 4; ++i) points.push_back(points[static_cast<std::size_t>(i)]);
        break;
      }
      default: {  // sphere points snapped to a coarse grid: many duplicates and coplanar groups
        for (const Vec3& p : test::SpherePoints(seed, n)) points.push_back((p * 4.0).array().round() / 4.0);
        break;
      }
    }
    auto hull = BuildHull(points);
    if (trial % 6 == 5 && !hull)
      continue;  // a coarse snap can leave a flat set; errors are checked elsewhere
    ASSERT_TRUE(hull) << "trial " << trial << ": " << hull.GetError().message;
    ASSERT_TRUE(CheckHull(hull.Value(), points)) << "trial " << trial;
    ++built;
  }
  EXPECT_GT(built, 2900);
}

TEST(HullBuilder, MillionPointsInBallBuildValidHull) {
  const auto points = test::BallPoints(99, 1000000);
  auto hull = BuildHull(points);
  ASSERT_TRUE(hull) << hull.GetError().message;
  // Check the invariants against the hull's own vertices (the full
  // brute-force check would be 1e6 x faces) plus every 97th input point.
  std::vector<Vec3> sample(hull.Value().Vertices().begin(), hull.Value().Vertices().end());
  for (std::size_t i = 0; i < points.size(); i += 97) sample.push_back(points[i]);
  EXPECT_TRUE(CheckHull(hull.Value(), sample));
}

}  // namespace hull_builder_test
}  // namespace talus
