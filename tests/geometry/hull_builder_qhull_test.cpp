// BuildHull against qhull (the independent truth) and the regression corpus
// of point sets that once broke the builder (tests/data/hulls/*.xyz).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "geometry/hull_check.h"
#include "talus/hull_builder.h"
#include "talus/reference/qhull_oracle.h"

namespace talus {
namespace hull_builder_qhull_test {

std::vector<std::array<double, 3>> SortedCoordinates(std::vector<Vec3> points) {
  std::vector<std::array<double, 3>> out;
  for (const Vec3& p : points) out.push_back({p.x(), p.y(), p.z()});
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// In general position the hull is unique: the vertex sets (as points) must
// be identical and the volumes agree to rounding (1e-12 relative: both sum
// O(F) exact-input determinants).
TEST(HullBuilderVsQhull, GeneralPositionGivesSameVerticesAndVolume) {
  for (int trial = 0; trial < 200; ++trial) {
    const auto seed = static_cast<std::uint64_t>(1000 + trial);
    const int n = 10 + 7 * trial;
    const auto points = trial % 2 ? test::SpherePoints(seed, n) : test::BallPoints(seed, n);
    auto ours = BuildHull(points);
    auto theirs = QhullConvexHull(points);
    ASSERT_TRUE(ours) << ours.GetError().message;
    ASSERT_TRUE(theirs) << theirs.GetError().message;
    const Hull& hull = ours.Value();
    std::vector<Vec3> qhullVertices;
    for (int i : theirs.Value().vertexIndices) qhullVertices.push_back(points[static_cast<std::size_t>(i)]);
    EXPECT_EQ(SortedCoordinates({hull.Vertices().begin(), hull.Vertices().end()}),
              SortedCoordinates(qhullVertices))
        << "trial " << trial;
    EXPECT_NEAR(test::HullVolume(hull), theirs.Value().volume, 1e-12 * theirs.Value().volume)
        << "trial " << trial;
  }
}

// With coplanar points (cube grids, snapped spheres, far offsets) qhull may
// keep or drop points on faces differently, so compare the volume (within
// 1e-9 relative: qhull merges facets with its own, larger tolerance) and
// check that every vertex of ours is extreme: it is a vertex of qhull's hull
// or lies on its boundary, i.e. removing it shrinks our hull's volume.
TEST(HullBuilderVsQhull, DegenerateSetsGiveSameVolumeAndExtremeVertices) {
  for (int trial = 0; trial < 60; ++trial) {
    const auto seed = static_cast<std::uint64_t>(5000 + trial);
    std::vector<Vec3> points;
    if (trial % 3 == 0) points = test::CubeWithSurfacePoints(seed, 200);
    if (trial % 3 == 1) {
      for (const Vec3& p : test::SpherePoints(seed, 300)) points.push_back((p * 4.0).array().round() / 4.0);
    }
    if (trial % 3 == 2) points = test::BallPoints(seed, 300, Vec3(1e4, 1e4, -1e4), 1.0);
    auto ours = BuildHull(points);
    auto theirs = QhullConvexHull(points);
    ASSERT_TRUE(ours) << ours.GetError().message;
    ASSERT_TRUE(theirs) << theirs.GetError().message;
    const double volume = test::HullVolume(ours.Value());
    EXPECT_NEAR(volume, theirs.Value().volume, 1e-9 * volume) << "trial " << trial;
    const std::vector<Vec3> vertices(ours.Value().Vertices().begin(), ours.Value().Vertices().end());
    for (std::size_t v = 0; v < vertices.size(); ++v) {
      std::vector<Vec3> without = vertices;
      without.erase(without.begin() + static_cast<std::ptrdiff_t>(v));
      auto smaller = BuildHull(without);
      ASSERT_TRUE(smaller) << smaller.GetError().message;
      EXPECT_LT(test::HullVolume(smaller.Value()), volume - 1e-9 * volume)
          << "trial " << trial << " vertex " << v;
    }
  }
}

TEST(HullBuilderRegression, EveryCorpusPointSetBuildsAValidHullMatchingQhull) {
  const std::filesystem::path dir = std::filesystem::path(TALUS_TEST_DATA_DIR) / "hulls";
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() == ".xyz") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  ASSERT_FALSE(files.empty());
  for (const auto& file : files) {
    const auto points = test::ReadXyz(file.string());
    ASSERT_GE(points.size(), 4u) << file;
    auto ours = BuildHull(points);
    ASSERT_TRUE(ours) << file << ": " << ours.GetError().message;
    EXPECT_TRUE(test::CheckHull(ours.Value(), points)) << file;
    auto theirs = QhullConvexHull(points);
    ASSERT_TRUE(theirs) << theirs.GetError().message;
    const double volume = test::HullVolume(ours.Value());
    EXPECT_NEAR(volume, theirs.Value().volume, 1e-9 * volume) << file;
  }
}

}  // namespace hull_builder_qhull_test
}  // namespace talus
