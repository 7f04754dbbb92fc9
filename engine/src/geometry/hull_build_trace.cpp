// Recording a Quickhull iteration (see hull_build_trace.h): walk the face
// pool in order (deterministic), copy every live or visible face's loop of
// input indices, and turn each horizon half-edge into its (origin, next
// origin) pair.
#include "geometry/hull_build_trace.h"

#include <vector>

namespace talus {

void RecordHullBuildStep(HullBuildTrace& trace, const QuickhullMesh& mesh, int eye,
                         std::span<const int> horizon) {
  HullBuildTraceStep step;
  step.eye = eye;
  std::vector<int> loop;
  for (int f = 0; f < mesh.FacePoolSize(); ++f) {
    const QhFaceState state = mesh.Face(f).state;
    if (state != QhFaceState::kAlive && state != QhFaceState::kVisible) continue;
    mesh.FaceLoop(f, loop);
    step.faces.push_back(loop);
    step.visible.push_back(state == QhFaceState::kVisible);
  }
  for (int e : horizon) {
    step.horizon.push_back({mesh.Edge(e).origin, mesh.Edge(mesh.Edge(e).next).origin});
  }
  trace.steps.push_back(std::move(step));
}

}  // namespace talus
