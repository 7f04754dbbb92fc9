// Contact manifolds between two convex polyhedra, built from the SAT's
// contact axis (section 2 of the write-up, "Contact Manifold Generation").
//
// Two generators (talus::ManifoldMode):
// - WriteUp: the write-up's rule. Edge axis: one point between the two
//   edges. Face axis: every vertex of either polyhedron within
//   kWriteUpPlaneTolerance of the contact (reference) plane and within
//   kWriteUpInsideTolerance of being inside the other polyhedron; all points
//   get the manifold's depth; more than kMaxManifoldPoints are reduced by
//   ReduceContactPoints.
// - Clipped: the incident face (the other polyhedron's face most
//   anti-parallel to the reference normal) clipped by the reference face's
//   side planes (Sutherland-Hodgman), points behind the reference plane
//   kept with their own depth, reduced to kClippedMaxPoints.
// Positions are midway between the two surfaces along the reference
// normal. Feature ids name the two features that made each point.
#pragma once

#include "collision/contact_manifold.h"
#include "collision/posed_hull.h"
#include "collision/sat.h"
#include "talus/narrow_phase.h"

namespace talus {

/// WriteUp: how far (metres) a vertex may be in front of the reference
/// plane (incident vertices) or behind it (reference vertices) and still
/// count. 5 mm: the write-up's "small tolerance", about a typical linear
/// slop, so resting points do not flicker in and out between steps.
inline constexpr double kWriteUpPlaneTolerance = 0.005;

/// WriteUp: how far (metres) outside the other polyhedron a vertex may be
/// and still count; the same reason and value as the plane tolerance.
inline constexpr double kWriteUpInsideTolerance = 0.005;

/// WriteUp: both tolerances are at most this fraction of the pair's length
/// scale (SatLengthScale). A slop is a small fraction of the bodies: 5 mm
/// is 1% of the write-up's half-metre boxes, and on a 1 mm hull an
/// absolute 5 mm took vertices five sizes away.
inline constexpr double kWriteUpRelative = 0.01;

/// WriteUp: the plane and inside tolerances for a pair (metres):
/// min(kWriteUpPlaneTolerance, kWriteUpRelative x SatLengthScale).
double WriteUpTolerance(const Hull& a, const Hull& b);

/// Clipped: a clipped point whose depth is within this many ulps of the
/// plane's offset and coordinates of the SAT's depth carries it (unitless;
/// the two are the same dot product, on vertices that tie in exact
/// arithmetic, rounded differently).
inline constexpr double kDepthRoundOffUlps = 64.0;

/// Clipped: most points kept (4 span any contact polygon well enough for a
/// stable solve; more only cost solver time).
inline constexpr int kClippedMaxPoints = 4;

/// Fills `out` for polyhedra `a` and `b` whose SAT answer `sat` is not
/// separated. `margin` (metres, >= 0): clipped points up to this far apart
/// are kept (negative depth). Always yields at least one point. `scratch`
/// (may be null) is the calling thread's working memory, as for RunSat.
void BuildPolyhedronManifold(const PosedHull& a, const PosedHull& b, const SatResult& sat, ManifoldMode mode,
                             double margin, ContactManifold* out, NarrowPhaseScratch* scratch = nullptr);

/// The parameters t for which p + t n (world, n unit) lies inside `hull`:
/// [*lo, *hi], empty when *lo > *hi, infinite ends when unbounded. A face
/// parallel to the line excludes it only when p lies outside it by more
/// than the hull's tolerance and `roundOff` (metres, >= 0: the round-off p
/// carries).
void LineInterval(const PosedHull& hull, const Vec3& p, const Vec3& n, double roundOff, double* lo,
                  double* hi);

/// The closest points of segments p0-p1 and q0-q1 (Ericson, Real-Time
/// Collision Detection 5.1.9), written to `onP` and `onQ`.
void ClosestPointsOfSegments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, Vec3* onP,
                             Vec3* onQ);

}  // namespace talus
