// The Separating Axis Test between two convex polyhedra (section 2 of the
// write-up, "Narrow phase - The Separating Axis Test").
//
// Two convex polyhedra are disjoint iff some plane separates them, and the
// only candidate normals are the face normals of either polyhedron and the
// cross products of an edge of one with an edge of the other (the face
// normals of the Minkowski difference A - B are among them). The SAT
// evaluates candidates, stops at the first separating one, and otherwise
// reports the axis of least overlap: the contact normal and penetration
// depth.
//
// The search runs in A's body frame (B moved there once per query); the
// axis it settles on is measured again in world space, so swapping A and B
// gives the same answer up to round-off (an edge axis eA x eB becomes
// eB x eA, negated exactly, in that final measure).
// The SatCache is the temporal coherence the write-up proposed: per pair, the
// last axis found; it is evaluated first and, if it still separates, the
// query ends there.
#pragma once

#include <cstdint>

#include "collision/posed_hull.h"
#include "talus/math.h"
#include "talus/narrow_phase.h"

namespace talus {

struct NarrowPhaseScratch;  // collision/narrow_phase_scratch.h

/// Which candidate an axis is.
enum class SatAxisType : std::uint8_t {
  None,      ///< no axis (empty cache)
  FaceA,     ///< normal of face indexA of A
  FaceB,     ///< normal of face indexB of B
  EdgePair,  ///< cross product of edge indexA of A and edge indexB of B
};

/// A candidate axis by the features that made it.
struct SatAxis {
  SatAxisType type = SatAxisType::None;
  int indexA = -1;  ///< face or edge of A (FaceA, EdgePair)
  int indexB = -1;  ///< face or edge of B (FaceB, EdgePair)

  friend bool operator==(const SatAxis&, const SatAxis&) = default;
};

/// Per-pair memory of the last SAT answer. Owned by whoever tracks the pair
/// across steps (the world's contact list); a default-constructed cache is
/// empty. It remembers the hulls it was filled for and ignores itself when
/// given another pair.
struct SatCache {
  const Hull* hullA = nullptr;
  const Hull* hullB = nullptr;
  SatAxis axis;            ///< last separating axis, or last contact axis
  bool separated = false;  ///< whether `axis` separated the pair last time
};
// Two to a cache line inside PairSatCache (docs/collision-narrow-phase.md,
// Record sizes).
static_assert(sizeof(SatCache) == 32, "SatCache: two hull pointers, a 12-byte axis and a flag");

/// The SAT's answer.
struct SatResult {
  bool separated = false;       ///< true when an axis shows a gap > the margin
  bool cacheHit = false;        ///< answered by the cached axis alone
  SatAxis axis;                 ///< the separating axis, or the contact axis
  Vec3 normal = Vec3::UnitY();  ///< world unit vector of `axis`, from B towards A
  /// Signed distance along `normal` (metres): the gap when separated, minus
  /// the penetration depth when overlapping.
  double separation = 0.0;
};

/// A face axis beats a face of A (or an edge axis beats the best face) only
/// if its separation is larger by more than this fraction of the pair's
/// length scale (SatLengthScale). Faces of A win ties over faces of B, and
/// faces over edges, which keeps the reference face stable from step to
/// step in resting contact; the reported depth is then at most this band
/// above the exact minimum. 1e-7 of the size: 0.1 micrometre on a metre
/// shape, four orders below a solver's slop (so no solver sees the
/// difference), eight orders above round-off (so faces that tie in exact
/// arithmetic, as parallel faces of stacked boxes do, keep their order).
/// Relative, not absolute: the old 1e-5 m was 1% of a 1 mm hull.
inline constexpr double kAxisPreferenceRelative = 1e-7;

/// The pair's length scale for the SAT's relative tolerances (metres): the
/// smaller of the two hulls' bounding-box half diagonals about their own
/// frames' vertex bounds, so a tolerance never exceeds a fraction of the
/// smaller shape.
double SatLengthScale(const Hull& a, const Hull& b);

/// The pair's length scale for round-off (metres): the larger of the two
/// half diagonals. A point the narrow phase builds (a corner of a large
/// face clipped down to a small one) carries the round-off of the larger
/// shape's coordinates, not the smaller's.
double RoundOffLengthScale(const Hull& a, const Hull& b);

/// The preference band of a pair in metres: kAxisPreferenceRelative x
/// SatLengthScale.
inline double AxisPreferenceBand(const Hull& a, const Hull& b) {
  return kAxisPreferenceRelative * SatLengthScale(a, b);
}

/// Edge pairs whose directions are parallel to within this sine are
/// skipped: their cross product has no reliable direction, and the face
/// normals already cover the axis they would give (unitless).
inline constexpr double kParallelEdgeSine = 1e-6;

/// Runs the SAT on `a` and `b`. A gap up to `margin` (metres, >= 0) still
/// counts as touching. `cache` (may be null) is read first and updated;
/// `stats` (may be null) is added to. `scratch` (may be null) is the calling
/// thread's working memory (collision/narrow_phase_scratch.h); without it
/// the query makes its own, which costs allocations.
SatResult RunSat(const PosedHull& a, const PosedHull& b, SatMode mode, double margin, SatCache* cache,
                 NarrowPhaseStats* stats, NarrowPhaseScratch* scratch = nullptr);

/// The separation of one candidate axis, as RunSat measures it; fills
/// `normal` (from B towards A). Returns -infinity for a degenerate
/// (parallel-edge) pair. Exposed for the cache and for tests.
double EvaluateSatAxis(const PosedHull& a, const PosedHull& b, const SatAxis& axis, Vec3* normal);

/// Gregorius' Gauss map test: edges (a, b) of A and (c, d) of B, given by the
/// normals of their two faces, build a face of the Minkowski difference iff
/// the arcs a-b and (-c)-(-d) cross on the unit sphere. `bxa` = b x a and
/// `dxc` = d x c are passed precomputed.
bool IsMinkowskiFace(const Vec3& a, const Vec3& b, const Vec3& bxa, const Vec3& c, const Vec3& d,
                     const Vec3& dxc);

}  // namespace talus
