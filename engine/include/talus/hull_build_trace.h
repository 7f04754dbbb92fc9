// HullBuildTrace: an optional record of every Quickhull iteration, for
// figures and teaching (the original write-up's figure 1: the hull growing
// point by point). BuildHull fills it when HullBuildSettings::trace points
// at one; otherwise nothing is recorded and nothing is paid.
//
// Each step is the hull just before one point (the eye) is added: every
// face of the current hull as a loop of input point indices, which of them
// the eye sees, and the horizon, the loop of edges between seen and unseen
// faces. The new cone is the triangles (a, b, eye) over the horizon edges
// (a, b). Indices refer to the points given to BuildHull, so a consumer
// needs no copy of the coordinates. Recording copies the whole hull per
// step (O(faces) each), so it is meant for small inputs (hundreds of points).
#pragma once

#include <array>
#include <vector>

namespace talus {

/// One Quickhull iteration: the hull before `eye` is added.
struct HullBuildTraceStep {
  /// Faces of the current hull, each a counter-clockwise (seen from
  /// outside) loop of input point indices; in the builder's face order.
  std::vector<std::vector<int>> faces;
  /// For each entry of `faces`: whether the eye sees it (it will be removed).
  std::vector<bool> visible;
  /// Input index of the point being added: the farthest outside point of
  /// the face being processed.
  int eye = -1;
  /// Horizon edges (a, b), input point indices, in order around the visible
  /// region; the cone that replaces the visible faces is (a, b, eye) each.
  std::vector<std::array<int, 2>> horizon;
};

/// Every iteration of one build, in order. Cleared by BuildHull before use.
/// The finished hull is BuildHull's result (its vertices are input points).
struct HullBuildTrace {
  std::vector<HullBuildTraceStep> steps;
};

}  // namespace talus
