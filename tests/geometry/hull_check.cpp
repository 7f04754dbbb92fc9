// Independent invariant checks and point generators for the builder tests.
#include "geometry/hull_check.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace talus::test {

double HullVolume(const Hull& hull) {
  const Vec3 origin = hull.Vertices()[0];
  double sixVolume = 0.0;
  for (const auto& t : hull.Triangulate()) {
    const Vec3 a = hull.Vertices()[static_cast<std::size_t>(t[0])] - origin;
    const Vec3 b = hull.Vertices()[static_cast<std::size_t>(t[1])] - origin;
    const Vec3 c = hull.Vertices()[static_cast<std::size_t>(t[2])] - origin;
    sixVolume += a.dot(b.cross(c));
  }
  return sixVolume / 6.0;
}

testing::AssertionResult CheckHull(const Hull& hull, const std::vector<Vec3>& points, double slack) {
  const double tol = hull.Tolerance();
  const auto vertices = hull.Vertices();
  const auto edges = hull.HalfEdges();
  const auto faces = hull.Faces();
  auto at = [](auto span, int i) -> const auto& { return span[static_cast<std::size_t>(i)]; };

  // Topology: twins, next/prev cycles, faces on the left, Euler.
  for (int h = 0; h < hull.HalfEdgeCount(); ++h) {
    const HullHalfEdge& e = at(edges, h);
    if (at(edges, e.twin).twin != h) return testing::AssertionFailure() << "twin of twin of " << h;
    if (at(edges, e.next).prev != h || at(edges, e.prev).next != h)
      return testing::AssertionFailure() << "links " << h;
    if (at(edges, e.next).face != e.face) return testing::AssertionFailure() << "next leaves face at " << h;
    if (at(edges, e.twin).face == e.face)
      return testing::AssertionFailure() << "face borders itself at " << h;
    if (at(edges, at(edges, e.twin).next).origin != e.origin)
      return testing::AssertionFailure() << "twin ends " << h;
  }
  if (hull.VertexCount() - hull.EdgeCount() + hull.FaceCount() != 2) {
    return testing::AssertionFailure() << "V - E + F != 2";
  }

  // Every vertex is an input point, bitwise.
  std::vector<std::array<double, 3>> sorted;
  for (const Vec3& p : points) sorted.push_back({p.x(), p.y(), p.z()});
  std::sort(sorted.begin(), sorted.end());
  for (int v = 0; v < hull.VertexCount(); ++v) {
    const Vec3& p = at(vertices, v);
    if (!std::binary_search(sorted.begin(), sorted.end(), std::array<double, 3>{p.x(), p.y(), p.z()})) {
      return testing::AssertionFailure() << "vertex " << v << " is not an input point";
    }
  }

  // Planar, convex faces; every input point behind every plane.
  for (int f = 0; f < hull.FaceCount(); ++f) {
    const Plane& plane = at(faces, f).plane;
    for (int v : hull.FaceVertices(f)) {
      if (std::abs(plane.SignedDistance(at(vertices, v))) > tol) {
        return testing::AssertionFailure() << "face " << f << " not planar at vertex " << v;
      }
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double d = plane.SignedDistance(points[i]);
      if (d > slack * tol) {
        return testing::AssertionFailure()
               << "point " << i << " is " << d << " m in front of face " << f << " (tolerance " << tol << ")";
      }
    }
  }

  // Adjacent faces are distinct planes: some neighbour vertex clearly below.
  for (int h = 0; h < hull.HalfEdgeCount(); ++h) {
    const HullHalfEdge& e = at(edges, h);
    const Plane& plane = at(faces, e.face).plane;
    double lowest = 0.0;
    for (int v : hull.FaceVertices(at(edges, e.twin).face)) {
      lowest = std::min(lowest, plane.SignedDistance(at(vertices, v)));
    }
    if (lowest >= -tol)
      return testing::AssertionFailure() << "faces across half-edge " << h << " are coplanar";
  }
  return testing::AssertionSuccess();
}

std::vector<Vec3> BallPoints(std::uint64_t seed, int count, const Vec3& center, double radius) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> points;
  while (static_cast<int>(points.size()) < count) {
    const Vec3 p(u(rng), u(rng), u(rng));
    if (p.squaredNorm() <= 1.0) points.push_back(center + radius * p);
  }
  return points;
}

std::vector<Vec3> SpherePoints(std::uint64_t seed, int count, double radius) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<Vec3> points;
  while (static_cast<int>(points.size()) < count) {
    const Vec3 p(g(rng), g(rng), g(rng));
    if (p.norm() > 1e-9) points.push_back(radius * p.normalized());
  }
  return points;
}

std::vector<Vec3> CubeWithSurfacePoints(std::uint64_t seed, int extra) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> grid(-4, 4);
  std::uniform_int_distribution<int> pick(0, 5);
  std::vector<Vec3> points;
  for (int i = 0; i < 8; ++i) points.emplace_back((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
  for (int i = 0; i < extra; ++i) {
    // A grid point (multiples of 1/4, exact in binary) pushed onto a face;
    // a third of them also onto an edge, some left inside.
    Vec3 p(grid(rng) / 4.0, grid(rng) / 4.0, grid(rng) / 4.0);
    const int face = pick(rng);
    if (face < 5) p[face % 3] = (face < 3) ? 1.0 : -1.0;
    if (i % 3 == 0) p[(face + 1) % 3] = 1.0;
    points.push_back(p);
  }
  return points;
}

std::vector<Vec3> ReadXyz(const std::string& path) {
  std::ifstream in(path);
  std::vector<Vec3> points;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    Vec3 p;
    if (fields >> p.x() >> p.y() >> p.z()) points.push_back(p);
  }
  return points;
}

}  // namespace talus::test
