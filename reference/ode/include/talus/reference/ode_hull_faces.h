// A convex hull's faces as ODE's dConvex takes them: one plane and one
// polygon per face. dCreateConvex reads "the number of vertices of the
// polygon, followed by the vertex indices" for each plane; qhull's
// triangulation gives a flat face as several triangles, which
// OdeHullFaces merges back into one face, as a user writes a hull.
#pragma once

#include <vector>

#include "talus/math.h"
#include "talus/reference/point_hull.h"

namespace talus::reference {

/// One face of a hull: its plane (outward unit normal, offset n . x for
/// every point x of the face) and its corners, indices into the hull's
/// vertices, counter-clockwise seen from outside.
struct HullFace {
  Vec3 normal;
  double offset = 0.0;
  std::vector<int> corners;
};

/// The faces of `hull`: its triangles whose planes agree to round-off
/// (normals within 1e-9, offsets within 1e-9 of the hull's size) merged
/// into one face, whose corners are ordered by angle about their mean.
std::vector<HullFace> OdeHullFaces(const PointHull& hull);

}  // namespace talus::reference
