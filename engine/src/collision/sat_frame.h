// SatFrame: the SAT's working memory for one query (collision/sat.cpp), kept
// in a thread's NarrowPhaseScratch so that steady-state queries allocate
// nothing.
#pragma once

#include <cstddef>
#include <vector>

#include "collision/posed_hull.h"
#include "talus/hull.h"
#include "talus/math.h"

namespace talus {

// Both hulls of one query in A's body frame. A's vertices, planes and face
// normals are read as stored; B's are moved into A's frame once, with one
// relative transform, instead of rotating each vertex or normal every time
// a face or edge query visits it. Filled per query into the calling
// thread's scratch (NarrowPhaseScratch: a query allocates only when a hull
// outgrows it; contents never leak into results). Only the axis search reads it: the reported axis is
// measured again in world space by EvaluateSatAxis.
struct SatFrame {
  // Per edge of either hull: the two faces' normals (the endpoints of the
  // edge's arc on the Gauss map) and their cross product (the arc's plane).
  // For B the normals are read through the face indices from planesB.
  struct Arc {
    Vec3 cross;      // normalRight x normalLeft, A's frame
    int left = -1;   // face of half-edge 2e
    int right = -1;  // face of half-edge 2e + 1
  };

  const Hull* hullA = nullptr;
  const Hull* hullB = nullptr;
  Mat3 rotation = Mat3::Identity();  // B's local axes in A's frame
  Vec3 translation = Vec3::Zero();   // B's origin in A's frame
  std::vector<Vec3> verticesB;       // B's vertices, A's frame
  std::vector<Plane> planesB;        // B's face planes, A's frame
  std::vector<Arc> arcsA;
  std::vector<Arc> arcsB;
  std::vector<double> sideB;  // per face of B: normal . (the current A arc's plane)

  // The stages fill what they need, so a pair separated by an early face
  // pays for no more than B's vertices.
  void FillVertices(const PosedHull& a, const PosedHull& b) {
    hullA = a.hull;
    hullB = b.hull;
    // B's local frame seen from A's: x_A = rotation * x_B + translation.
    rotation = a.rotation.transpose() * b.rotation;
    translation = a.rotation.transpose() * (b.position - a.position);
    const auto localB = hullB->Vertices();
    verticesB.resize(localB.size());
    for (std::size_t v = 0; v < localB.size(); ++v) verticesB[v] = rotation * localB[v] + translation;
  }

  void FillPlanes() {
    const auto facesB = hullB->Faces();
    planesB.resize(facesB.size());
    for (std::size_t f = 0; f < facesB.size(); ++f) {
      const Vec3 n = rotation * facesB[f].plane.normal;
      planesB[f] = {.normal = n, .offset = facesB[f].plane.offset + n.dot(translation)};
    }
  }

  void FillArcs() {
    const auto facesA = hullA->Faces();
    ArcsOf(
        *hullA, [&](int f) { return facesA[static_cast<std::size_t>(f)].plane.normal; }, &arcsA);
    ArcsOf(
        *hullB, [&](int f) { return planesB[static_cast<std::size_t>(f)].normal; }, &arcsB);
    sideB.resize(planesB.size());
  }

  template <typename NormalOf>
  static void ArcsOf(const Hull& hull, NormalOf normalOf, std::vector<Arc>* arcs) {
    const auto halfEdges = hull.HalfEdges();
    arcs->resize(static_cast<std::size_t>(hull.EdgeCount()));
    for (std::size_t e = 0; e < arcs->size(); ++e) {
      Arc& arc = (*arcs)[e];
      arc.left = halfEdges[2 * e].face;
      arc.right = halfEdges[2 * e + 1].face;
      arc.cross = normalOf(arc.right).cross(normalOf(arc.left));
    }
  }
};

}  // namespace talus
