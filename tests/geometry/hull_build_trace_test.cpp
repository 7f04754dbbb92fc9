// The optional Quickhull trace (talus/hull_build_trace.h): what the
// report's figure-1 view draws must be a faithful record of the build.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "talus/hull_builder.h"

namespace talus {
namespace hull_build_trace_test {

// A cube's 8 corners plus its centre: the tetrahedron takes 4 corners, the
// other 4 are added one step each, and the centre is never an eye.
std::vector<Vec3> CubeWithCentre() {
  std::vector<Vec3> points;
  for (int i = 0; i < 8; ++i) points.emplace_back(i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0);
  points.emplace_back(0.0, 0.0, 0.0);
  return points;
}

TEST(HullBuildTrace, CubeTraceAddsEachRemainingCornerOnceAndNeverTheCentre) {
  const std::vector<Vec3> points = CubeWithCentre();
  HullBuildTrace trace;
  auto hull = BuildHull(points, {.trace = &trace});
  ASSERT_TRUE(hull) << hull.GetError().message;
  ASSERT_EQ(trace.steps.size(), 4u);
  std::set<int> eyes;
  for (const HullBuildTraceStep& step : trace.steps) {
    eyes.insert(step.eye);
    EXPECT_NE(step.eye, 8);
  }
  EXPECT_EQ(eyes.size(), 4u);
  // The first step is the initial tetrahedron: four triangles.
  EXPECT_EQ(trace.steps.front().faces.size(), 4u);
}

TEST(HullBuildTrace, EachStepsHorizonIsAClosedLoopBetweenSeenAndUnseenFaces) {
  const std::vector<Vec3> points = CubeWithCentre();
  HullBuildTrace trace;
  ASSERT_TRUE(BuildHull(points, {.trace = &trace}));
  for (const HullBuildTraceStep& step : trace.steps) {
    ASSERT_EQ(step.faces.size(), step.visible.size());
    ASSERT_GE(step.horizon.size(), 3u);
    EXPECT_TRUE(std::any_of(step.visible.begin(), step.visible.end(), [](bool v) { return v; }));
    // Consecutive horizon edges chain end to start, and the loop closes.
    for (std::size_t i = 0; i < step.horizon.size(); ++i) {
      EXPECT_EQ(step.horizon[i][1], step.horizon[(i + 1) % step.horizon.size()][0]);
    }
    // Every horizon edge (a, b) lies on a visible face and its reverse (b, a) on a hidden one.
    for (const auto& [a, b] : step.horizon) {
      bool onVisible = false, reverseOnHidden = false;
      for (std::size_t f = 0; f < step.faces.size(); ++f) {
        const auto& loop = step.faces[f];
        for (std::size_t k = 0; k < loop.size(); ++k) {
          const int from = loop[k], to = loop[(k + 1) % loop.size()];
          if (from == a && to == b && step.visible[f]) onVisible = true;
          if (from == b && to == a && !step.visible[f]) reverseOnHidden = true;
        }
      }
      EXPECT_TRUE(onVisible && reverseOnHidden) << "edge " << a << " -> " << b;
    }
  }
}

TEST(HullBuildTrace, TracingDoesNotChangeTheHullAndIsClearedOnReuse) {
  const std::vector<Vec3> points = CubeWithCentre();
  HullBuildTrace trace;
  auto traced = BuildHull(points, {.trace = &trace});
  auto plain = BuildHull(points);
  ASSERT_TRUE(traced && plain);
  ASSERT_EQ(traced.Value().VertexCount(), plain.Value().VertexCount());
  for (int v = 0; v < plain.Value().VertexCount(); ++v) {
    EXPECT_EQ(traced.Value().Vertices()[static_cast<std::size_t>(v)],
              plain.Value().Vertices()[static_cast<std::size_t>(v)]);
  }
  EXPECT_EQ(traced.Value().FaceCount(), plain.Value().FaceCount());
  ASSERT_TRUE(BuildHull(points, {.trace = &trace}));
  EXPECT_EQ(trace.steps.size(), 4u);
}

}  // namespace hull_build_trace_test
}  // namespace talus
