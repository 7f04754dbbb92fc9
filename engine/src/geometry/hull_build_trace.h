// Recording one Quickhull iteration into a HullBuildTrace (talus/
// hull_build_trace.h). Kept out of the builder so that the builder's only
// cost when tracing is off is one pointer test per added point.
//
// Invariant expected from the caller: the horizon has been computed for
// the eye (faces the eye sees are marked kVisible, none deleted yet), and
// `horizon` lists the horizon half-edges, which lie on visible faces.
#pragma once

#include <span>

#include "geometry/quickhull_mesh.h"
#include "talus/hull_build_trace.h"

namespace talus {

/// Appends the hull of `mesh` as the eye `eye` sees it to `trace`.
void RecordHullBuildStep(HullBuildTrace& trace, const QuickhullMesh& mesh, int eye,
                         std::span<const int> horizon);

}  // namespace talus
