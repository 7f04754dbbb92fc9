// The narrow phase's entry point: one pair of shapes in, at most one
// contact manifold out, dispatched on the pair's shape types.
//
// The dispatch table is a ShapeType x ShapeType array of functions. Each
// routine is written once for one order (polyhedron-polyhedron, sphere-X);
// the mirrored entries call it with A and B swapped and then flip the
// normal and swap the two halves of every feature id, so swapping A and B
// changes the normal's sign and nothing else.
#pragma once

#include "collision/contact_manifold.h"
#include "collision/sat.h"
#include "talus/narrow_phase.h"
#include "talus/shape.h"
#include "talus/transform.h"

namespace talus {

/// Tests shapes `a` and `b` at the given world transforms. Returns true and
/// fills `manifold` (normal from B towards A) when they touch or are within
/// settings.speculativeMargin. `cache` (may be null) is the pair's SAT cache
/// (used for polyhedron pairs when settings.useSatCache); `stats` (may be
/// null) is added to. When it returns false, `manifold` holds the
/// separating axis (normal, from B towards A) and minus the gap along it
/// (depth < -margin), with no points. `scratch` (may be null) is the calling
/// thread's working memory (collision/narrow_phase_scratch.h: the step
/// passes the scratch of the pool thread that runs the pair).
bool Collide(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
             const NarrowPhaseSettings& settings, SatCache* cache, NarrowPhaseStats* stats,
             ContactManifold* manifold, NarrowPhaseScratch* scratch = nullptr);

}  // namespace talus
