// Hull::FromPolygons: the validated door every hull goes through.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "talus/hull.h"

namespace talus {
namespace hull_test {

// A regular-ish tetrahedron, counter-clockwise from outside.
std::vector<Vec3> TetraPoints() { return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}; }
std::vector<std::vector<int>> TetraFaces() { return {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}; }

TEST(Hull, BoxHasSixQuadFacesTwelveEdgesEightVertices) {
  auto box = Hull::Box({1, 2, 3});
  ASSERT_TRUE(box) << box.GetError().message;
  const Hull& hull = box.Value();
  EXPECT_EQ(hull.VertexCount(), 8);
  EXPECT_EQ(hull.EdgeCount(), 12);
  EXPECT_EQ(hull.FaceCount(), 6);
  for (int f = 0; f < hull.FaceCount(); ++f) EXPECT_EQ(hull.FaceVertices(f).size(), 4u);
  EXPECT_EQ(hull.Triangulate().size(), 12u);
}

TEST(Hull, BoxFacePlanesPointOutwardAtHalfExtents) {
  const Hull hull = Hull::Box({1, 2, 3}).Value();
  for (const HullFace& face : hull.Faces()) {
    const Vec3 n = face.plane.normal;
    EXPECT_NEAR(n.norm(), 1.0, 1e-15);
    EXPECT_NEAR(face.plane.offset, n.cwiseAbs().dot(Vec3(1, 2, 3)), 1e-15);
  }
}

TEST(Hull, HalfEdgeLinksAreConsistent) {
  const Hull hull = Hull::Box({1, 1, 1}).Value();
  const auto edges = hull.HalfEdges();
  for (int h = 0; h < hull.HalfEdgeCount(); ++h) {
    const HullHalfEdge& e = edges[static_cast<std::size_t>(h)];
    EXPECT_EQ(e.twin, h ^ 1) << "twins are paired (2e, 2e + 1)";
    EXPECT_EQ(edges[static_cast<std::size_t>(e.twin)].twin, h);
    EXPECT_EQ(edges[static_cast<std::size_t>(e.next)].prev, h);
    EXPECT_EQ(edges[static_cast<std::size_t>(e.next)].face, e.face);
    EXPECT_EQ(edges[static_cast<std::size_t>(e.twin)].origin, edges[static_cast<std::size_t>(e.next)].origin);
  }
  for (int v = 0; v < hull.VertexCount(); ++v) {
    EXPECT_EQ(edges[static_cast<std::size_t>(hull.VertexEdges()[static_cast<std::size_t>(v)])].origin, v);
  }
}

TEST(Hull, TetrahedronIsAccepted) {
  auto tetra = Hull::FromPolygons(TetraPoints(), TetraFaces());
  ASSERT_TRUE(tetra) << tetra.GetError().message;
  EXPECT_EQ(tetra.Value().EdgeCount(), 6);
}

TEST(Hull, InsideOutTetrahedronIsRefused) {
  auto faces = TetraFaces();
  for (auto& f : faces) std::reverse(f.begin(), f.end());
  auto tetra = Hull::FromPolygons(TetraPoints(), faces);
  ASSERT_FALSE(tetra);
  EXPECT_NE(tetra.GetError().message.find("concave"), std::string::npos) << tetra.GetError().message;
}

TEST(Hull, OpenSurfaceIsRefused) {
  auto faces = TetraFaces();
  faces.pop_back();
  faces.push_back({1, 2, 3});
  faces.push_back({0, 1, 2});  // reuses edge 0->2 reversed twice: not a manifold
  auto result = Hull::FromPolygons(TetraPoints(), faces);
  ASSERT_FALSE(result);
}

TEST(Hull, MissingFaceIsRefusedAsNotClosed) {
  auto faces = TetraFaces();
  faces.pop_back();
  std::vector<Vec3> points = TetraPoints();
  points.push_back({5, 5, 5});
  faces.push_back({1, 2, 4});
  auto result = Hull::FromPolygons(points, faces);
  ASSERT_FALSE(result);
  EXPECT_NE(result.GetError().message.find("no twin"), std::string::npos) << result.GetError().message;
}

TEST(Hull, NonFiniteVertexIsRefusedByIndex) {
  auto points = TetraPoints();
  points[2].y() = std::numeric_limits<double>::quiet_NaN();
  auto result = Hull::FromPolygons(points, TetraFaces());
  ASSERT_FALSE(result);
  EXPECT_EQ(result.GetError().message, "vertex 2 is not finite");
}

TEST(Hull, OutOfRangeIndexIsRefused) {
  auto faces = TetraFaces();
  faces[1][2] = 9;
  auto result = Hull::FromPolygons(TetraPoints(), faces);
  ASSERT_FALSE(result);
  EXPECT_NE(result.GetError().message.find("face 1 refers to vertex 9"), std::string::npos);
}

TEST(Hull, CoplanarAdjacentFacesAreRefused) {
  // A box whose +z face is split into two triangles.
  const Hull box = Hull::Box({1, 1, 1}).Value();
  std::vector<Vec3> points(box.Vertices().begin(), box.Vertices().end());
  std::vector<std::vector<int>> faces = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3}, {0, 1, 5, 4},
                                         {4, 5, 7},    {4, 7, 6},    {0, 2, 3, 1}};
  auto result = Hull::FromPolygons(points, faces);
  ASSERT_FALSE(result);
  EXPECT_NE(result.GetError().message.find("coplanar"), std::string::npos) << result.GetError().message;
}

TEST(Hull, BoxWithNonPositiveExtentIsRefused) {
  EXPECT_FALSE(Hull::Box({1, 0, 1}));
  EXPECT_FALSE(Hull::Box({1, -1, 1}));
  EXPECT_FALSE(Hull::Box({1, std::numeric_limits<double>::infinity(), 1}));
}

}  // namespace hull_test
}  // namespace talus
