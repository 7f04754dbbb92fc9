// Convex hull of a point cloud via qhull (reentrant API, libqhull_r).
//
// qhull runs with "Qt" (triangulated output) so every facet is a triangle;
// each triangle is oriented by comparing its winding normal with qhull's
// outward facet normal. Vertices are renumbered densely in first-use order,
// which follows qhull's facet list and is deterministic for a given input.
#include "talus/reference/point_hull.h"

#include <cmath>
#include <cstdio>
#include <string>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace talus::reference {

Result<PointHull> ComputePointHull(std::span<const Vec3> points) {
  if (points.size() < 4) return Error{"hull: needs at least 4 points, got " + std::to_string(points.size())};
  std::vector<coordT> coordinates;
  coordinates.reserve(points.size() * 3);
  for (size_t i = 0; i < points.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      if (!std::isfinite(points[i][axis])) {
        return Error{"hull: point " + std::to_string(i) + ": coordinate is not finite"};
      }
      coordinates.push_back(points[i][axis]);
    }
  }

  // qhull reports errors on a stream; a temporary file keeps them off stderr.
  FILE* errors = std::tmpfile();
  qhT state;
  qhT* qh = &state;
  qh_zero(qh, errors);
  char options[] = "qhull Qt";
  const int exitCode = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coordinates.data(), False,
                                    options, nullptr, errors);
  PointHull hull;
  if (exitCode == 0) {
    std::vector<int> remap(points.size(), -1);
    facetT* facet;
    FORALLfacets {
      std::array<int, 3> triangle{};
      int corner = 0;
      vertexT* vertex;
      vertexT** vertexp;
      FOREACHvertex_(facet->vertices) {
        if (corner == 3) break;
        const int id = qh_pointid(qh, vertex->point);
        if (remap[id] < 0) {
          remap[id] = static_cast<int>(hull.vertices.size());
          hull.vertices.push_back(points[id]);
        }
        triangle[corner++] = remap[id];
      }
      const Vec3 facetNormal(facet->normal[0], facet->normal[1], facet->normal[2]);
      const Vec3& a = hull.vertices[triangle[0]];
      const Vec3 winding = (hull.vertices[triangle[1]] - a).cross(hull.vertices[triangle[2]] - a);
      if (winding.dot(facetNormal) < 0.0) std::swap(triangle[1], triangle[2]);
      hull.triangles.push_back(triangle);
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0;
  int totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  if (errors != nullptr) std::fclose(errors);
  if (exitCode != 0) {
    return Error{"hull: the points span no volume (qhull error " + std::to_string(exitCode) +
                 "; all points coincident, collinear or coplanar?)"};
  }
  return hull;
}

}  // namespace talus::reference
