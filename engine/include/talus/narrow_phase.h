// Narrow-phase settings and statistics: the public knobs the world and the
// testbed use to select the Separating Axis Test variant and the contact
// point generator, and the counters the narrow phase reports.
//
// The write-up's choices (full SAT, vertices-near-the-plane contact points)
// stay available as the reference; the faster or more accurate variants are
// options whose worth the testbed measures.
#pragma once

#include <cstdint>

namespace talus {

/// How the Separating Axis Test between two convex polyhedra searches its
/// candidate axes. Both modes give the same verdict and, up to exact ties,
/// the same contact axis (see docs/collision-narrow-phase.md).
enum class SatMode {
  /// The write-up's test: every face normal of both polyhedra and the cross
  /// product of every edge pair, 2F + E^2 axes, each edge axis measured by
  /// projecting both polyhedra. The reference; slow for large hulls.
  Full,
  /// Edge pairs pruned by the Gauss map test: only pairs whose arcs cross on
  /// the unit sphere build a face of the Minkowski difference, and only
  /// those can be the minimum or a separating axis (Gregorius, GDC 2013,
  /// "The Separating Axis Test between convex polyhedra").
  GaussMapPruned,
};

/// How the contact points of a polyhedron-polyhedron manifold are made.
enum class ManifoldMode {
  /// The write-up's: for an edge axis the closest points of the two edges;
  /// for a face axis every vertex of either polyhedron close to the contact
  /// plane and (almost) inside the other polyhedron, all with the
  /// manifold's single depth; at most kMaxManifoldPoints (8).
  WriteUp,
  /// The incident face clipped against the reference face's side planes
  /// (Sutherland-Hodgman); each point has its own depth and a feature id;
  /// reduced to at most 4 points (deepest, then largest area).
  Clipped,
};

/// Whether a polyhedron pair's manifold remembers points across steps
/// (read by the World's contact stage; Collide() is always fresh).
enum class ManifoldPersistence {
  /// Each step's manifold is the narrow phase's alone (the write-up's).
  Fresh,
  /// A fresh manifold of a single point (an edge crossing an edge, a lone
  /// vertex) is filled up to 4 points with points of earlier steps whose
  /// two surface points, refreshed from the current poses, have neither
  /// separated nor slid apart by more than
  /// NarrowPhaseSettings::persistenceDistance (Bullet's persistent
  /// manifold idea; collision/manifold_persistence.h). A single-point edge
  /// contact under load then keeps the support it had.
  Accumulate,
};

/// Narrow-phase options; the defaults are the recommended (fast, accurate)
/// choices, not the write-up's.
struct NarrowPhaseSettings {
  SatMode satMode = SatMode::GaussMapPruned;          ///< axis search, see SatMode
  ManifoldMode manifoldMode = ManifoldMode::Clipped;  ///< point generator, see ManifoldMode
  bool useSatCache = true;  ///< try each pair's last axis first (temporal coherence)
  /// Speculative margin in metres (>= 0, default 0): pairs closer than this
  /// but not touching still get a manifold, with negative depths.
  double speculativeMargin = 0.0;
  /// Manifold reuse distance in metres, finite and >= 0; 0 turns reuse off.
  /// A polyhedron pair that had a manifold last step skips the SAT and the
  /// clipping while no point of either body has moved more than this
  /// relative to the other since the narrow phase last computed the pair's
  /// manifold: the manifold is rebuilt from points stored in the bodies'
  /// frames, with depths re-measured from the current poses (Jolt's
  /// body-pair cache; collision/manifold_reuse.h bounds the depth error).
  /// Pairs with a sphere always run the narrow phase (it is a closed form,
  /// nothing to save, and a rolling ball turns by more than it moves).
  /// Read by the World's contact stage; Collide() ignores it. Default
  /// 0.5 mm, half Jolt's 1 mm (and stricter than Jolt's 2 degrees for any
  /// body of radius above 1.5 cm, since a turn counts by how far it moves
  /// the body's farthest point). Measured (docs/collision-narrow-phase.md):
  /// at 1 mm the 1000-hull pile still moves at 237 J at step 600 (64 J
  /// without reuse), at 0.5 mm 48 J; 0.25 mm saves less time on the pile.
  double reuseDistance = 0.0005;
  /// Whether points persist across steps, see ManifoldPersistence. Default
  /// Accumulate: the 1000-hull pile's deepest contact at step 600 went from
  /// 4.1 cm to 5.0 mm and its kinetic energy from 62.5 J to 1e-6 J, with
  /// every testbed verdict unchanged (docs/collision-narrow-phase.md).
  ManifoldPersistence persistence = ManifoldPersistence::Accumulate;
  /// Break distance of a remembered point in metres, finite and > 0: it is
  /// dropped once its two surface points separated along the normal or slid
  /// apart along the surfaces by more than this (then it no longer marks a
  /// place where the shapes touch), or when it lies this close to a kept
  /// point (it adds no support). At most 1% of the smaller body's
  /// bounding radius is used (kPersistentRelative). Default 5 mm, of the
  /// order of the Baumgarte slop (WorldSettings::slop): a remembered point
  /// is then about as far from the true contact as a resting one is allowed
  /// to sink. The measurements that chose it (the 1000-hull pile at several
  /// distances) are in docs/collision-narrow-phase.md.
  double persistenceDistance = 0.005;

  /// Field by field (MethodSettings compares its narrow phase with it).
  friend bool operator==(const NarrowPhaseSettings&, const NarrowPhaseSettings&) = default;
};

/// Counters accumulated by the narrow phase (add-only; the world resets
/// them each step).
struct NarrowPhaseStats {
  std::int64_t pairsTested = 0;      ///< shape pairs given to the narrow phase
  std::int64_t pairsTouching = 0;    ///< of those, pairs that produced a manifold
  std::int64_t satTests = 0;         ///< polyhedron-polyhedron SAT queries run
  std::int64_t satCacheHits = 0;     ///< SAT queries answered by the cached separating axis alone
  std::int64_t faceAxesTested = 0;   ///< face normals evaluated
  std::int64_t edgeAxesTested = 0;   ///< edge-pair cross products evaluated
  std::int64_t edgePairsPruned = 0;  ///< edge pairs rejected by the Gauss map test
  std::int64_t manifoldPoints = 0;   ///< contact points produced (manifold points)

  /// Adds another set of counters to this one.
  NarrowPhaseStats& operator+=(const NarrowPhaseStats& other) {
    pairsTested += other.pairsTested;
    pairsTouching += other.pairsTouching;
    satTests += other.satTests;
    satCacheHits += other.satCacheHits;
    faceAxesTested += other.faceAxesTested;
    edgeAxesTested += other.edgeAxesTested;
    edgePairsPruned += other.edgePairsPruned;
    manifoldPoints += other.manifoldPoints;
    return *this;
  }
};

}  // namespace talus
