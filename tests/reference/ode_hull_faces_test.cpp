// The faces the ODE backend gives dConvex (OdeHullFaces): each flat face of
// a hull is one polygon, its corners on the face's plane and counter-
// clockwise seen from outside, as dCreateConvex reads them.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "talus/reference/ode_hull_faces.h"
#include "talus/reference/point_hull.h"

#include "peer_fixture.h"

namespace talus::reference {
namespace ode_hull_faces_test {

// Round-off on coordinates of size ~1 m: a corner off its plane, or a turn
// the wrong way, is off by the hull's own size, not by 1e-12.
constexpr double kRoundOff = 1e-12;

// Each face: corners on its plane, strictly convex and counter-clockwise
// about its outward normal; and the faces together triangulate into as many
// triangles as qhull gave (a k-gon is k - 2 triangles), so none is lost.
void ExpectValidFaces(const PointHull& hull, const std::vector<HullFace>& faces) {
  std::size_t triangles = 0;
  for (const HullFace& face : faces) {
    ASSERT_GE(face.corners.size(), 3u);
    EXPECT_NEAR(face.normal.norm(), 1.0, kRoundOff);
    triangles += face.corners.size() - 2;
    const std::size_t n = face.corners.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& a = hull.vertices[face.corners[i]];
      const Vec3& b = hull.vertices[face.corners[(i + 1) % n]];
      const Vec3& c = hull.vertices[face.corners[(i + 2) % n]];
      EXPECT_NEAR(face.normal.dot(a), face.offset, kRoundOff);
      EXPECT_GT((b - a).cross(c - b).dot(face.normal), kRoundOff) << "corner " << i << " turns the wrong way";
    }
  }
  EXPECT_EQ(triangles, hull.triangles.size());
}

TEST(OdeHullFaces, ACubeIsSixSquaresNotTwelveTriangles) {
  std::vector<Vec3> points;
  for (double x : {-0.5, 0.5})
    for (double y : {-0.5, 0.5})
      for (double z : {-0.5, 0.5}) points.emplace_back(x, y, z);
  auto hull = ComputePointHull(points);
  ASSERT_TRUE(hull) << hull.GetError().message;
  ASSERT_EQ(hull.Value().triangles.size(), 12u);
  const std::vector<HullFace> faces = OdeHullFaces(hull.Value());
  ASSERT_EQ(faces.size(), 6u);
  for (const HullFace& face : faces) {
    EXPECT_EQ(face.corners.size(), 4u);
    EXPECT_NEAR(face.offset, 0.5, kRoundOff);                        // every face 0.5 m from the centre
    EXPECT_NEAR(face.normal.cwiseAbs().maxCoeff(), 1.0, kRoundOff);  // along an axis
  }
  ExpectValidFaces(hull.Value(), faces);
}

TEST(OdeHullFaces, ATetrahedronKeepsItsFourTriangles) {
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  auto hull = ComputePointHull(points);
  ASSERT_TRUE(hull) << hull.GetError().message;
  const std::vector<HullFace> faces = OdeHullFaces(hull.Value());
  EXPECT_EQ(faces.size(), 4u);
  ExpectValidFaces(hull.Value(), faces);
}

TEST(OdeHullFaces, HullRestsBottomFaceIsOneQuadrilateral) {
  // The shipped hull_rest hull: its four bottom points are coplanar (y = 0),
  // which qhull gives as two triangles.
  const harness::Run run = test::LoadRun("stacking/hull_rest.json");
  ASSERT_FALSE(run.scenario.bodies.empty());
  auto hull = ComputePointHull(std::get<harness::HullShape>(run.scenario.bodies[1].shape).points);
  ASSERT_TRUE(hull) << hull.GetError().message;
  const std::vector<HullFace> faces = OdeHullFaces(hull.Value());
  int bottoms = 0;
  for (const HullFace& face : faces) {
    if (face.normal.dot(Vec3(0, -1, 0)) < 1.0 - kRoundOff) continue;
    ++bottoms;
    EXPECT_EQ(face.corners.size(), 4u);
    EXPECT_NEAR(face.offset, 0.0, kRoundOff);
  }
  EXPECT_EQ(bottoms, 1);
  ExpectValidFaces(hull.Value(), faces);
}

}  // namespace ode_hull_faces_test
}  // namespace talus::reference
