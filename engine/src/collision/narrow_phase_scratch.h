// NarrowPhaseScratch: one thread's working memory for the narrow phase
// (the SAT's frame, the clipper's polygons, the manifold's candidate
// points). The world keeps one per thread of its job pool
// (JobPool::ThreadScratch) and hands each pair the scratch of the thread
// that runs it, so steady-state pairs allocate nothing and no two threads
// share a buffer. Contents never leak into results: every buffer is
// cleared or overwritten before it is read, so the same pair gives the same
// bits in any thread's scratch (docs/threading.md).
#pragma once

#include <cstdint>
#include <vector>

#include "collision/contact_manifold.h"
#include "collision/sat_frame.h"
#include "talus/math.h"

namespace talus {

// A polygon vertex during clipping: its position, the features that made
// it, and the line the polygon follows to the next vertex (an incident edge,
// or a reference side plane already clipped against).
struct ClipVertex {
  Vec3 position;
  std::uint32_t referenceFeature;
  std::uint32_t incidentFeature;
  std::uint32_t segmentIncident;    // incident feature of the segment to the next vertex
  bool segmentOnReference = false;  // the segment lies on a reference side plane
  int segmentReferenceEdge = -1;    // the reference half-edge of that side plane
};
// Copied at every side plane the polygon is clipped against
// (docs/collision-narrow-phase.md, Record sizes).
static_assert(sizeof(ClipVertex) == 48, "ClipVertex: position, three feature ids, a flag and an edge");

/// The polyhedron manifold's buffers (collision/polyhedron_manifold.cpp).
struct ManifoldScratch {
  std::vector<ClipVertex> polygon;  ///< the incident face as it is clipped
  std::vector<ClipVertex> clipped;  ///< the clipper's output, swapped with `polygon`
  std::vector<ContactPoint> kept;   ///< Clipped: points before reduction
  std::vector<ContactPoint> found;  ///< WriteUp: points before reduction
};

struct NarrowPhaseScratch {
  SatFrame sat;
  ManifoldScratch manifold;
};

}  // namespace talus
