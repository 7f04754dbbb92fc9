// Persistent contact points: a polyhedron pair's manifold that keeps the
// points of earlier steps while they still describe touching surfaces, so
// that a contact the narrow phase sees as a single point this step (two
// edges crossing under load) keeps the support of the points it had before.
// This is the idea of Bullet's btPersistentManifold (E. Coumans): up to four
// points, each refreshed from the current poses, dropped once the surfaces
// drifted apart; the rules and thresholds here are our own.
//
// Why: a single-point edge-edge contact cannot resist a torque about the
// point, so a hull resting on another's edge tips into it under the weight
// of a pile; the fresh narrow phase gives one point each step and the solver
// pushes only there. Points remembered from the steps before (where the
// contact was a face, or another edge pair) span the support the bodies
// really have.
//
// A remembered point is a pair of surface points, A's in A's frame and B's
// in B's (ManifoldAnchors); at the current poses they are pA and pB, its
// depth along the fresh normal n is (pB - pA) . n and its tangential drift
// |(pB - pA) - depth n|. Both points lie on their bodies' surfaces
// (SnapAnchorsToSurfaces) at every pose, so no remembered point can be
// deeper than the SAT's least overlap along n (for pA in A and pB in B,
// (pB - pA) . n <= max_B n.x - min_A n.x): the fresh deepest point keeps
// carrying the SAT depth.
//
// Rules (MergePersistentPoints):
// - only a fresh manifold of at most kPersistentFreshPoints points (one)
//   whose deepest point penetrates (depth > 0: the contact is under load)
//   is filled, and its points are always kept; a speculative contact (a
//   gap) is left as the narrow phase made it;
// - a remembered point is dropped when it separated along n by more than
//   the distance, drifted tangentially by more than the distance, has the
//   feature id of a fresh point (the fresh one replaces it) or lies within
//   the distance of a kept point (it adds no support);
// - survivors fill the manifold up to kPersistentMaxPoints, each time the
//   one that grows the kept points' area in the contact plane most (the
//   farthest while fewer than two are kept); ties to the lower index.
// Remembered points keep their feature ids, so warm starting finds their
// impulses; a point with a gap (negative depth) acts as a speculative
// contact in the solver.
#pragma once

#include "collision/contact_manifold.h"
#include "collision/manifold_reuse.h"
#include "talus/shape.h"
#include "talus/transform.h"

namespace talus {

/// Most points a persistent manifold holds (unitless): four span any
/// contact polygon, as for the clipped generator.
inline constexpr int kPersistentMaxPoints = 4;

/// The World fills only fresh manifolds of at most this many points
/// (unitless): single-point contacts (an edge crossing an edge, a lone
/// vertex) are the ones that cannot resist a torque about their point.
/// Measured (docs/collision-narrow-phase.md): filling up to 3 fresh points
/// as well held the hull piles equally (5.0 mm) but doubled the box
/// pyramids' drift (H = 10: 4.3e-5 m without persistence, 7.2e-5 m up to
/// 3, 4.1e-5 m with 1), as boxes tilted on two corners kept their lifted
/// corners as speculative points.
inline constexpr int kPersistentFreshPoints = 1;

/// The break distance is at most this fraction of the smaller body's
/// bounding-sphere radius (unitless): a remembered point may sit that far
/// from where the surfaces touch, so on a 1 cm body an absolute 5 mm would
/// be half its size (the same 1% as the write-up's tolerances,
/// kWriteUpRelative).
inline constexpr double kPersistentRelative = 0.01;

/// The break distance (metres) for a pair: min(`setting`,
/// kPersistentRelative x the smaller of the radii `radiusA`, `radiusB`).
double PersistentBreakDistance(double setting, double radiusA, double radiusB);

/// Puts the anchors of each point of a fresh polyhedron manifold (recorded
/// by RecordAnchors as position -+ depth/2 along the normal) on the two
/// surfaces. The narrow phase may have moved a point along its normal line
/// into both shapes (a side face leaning over an incident corner), which
/// shifts midpoint anchors off the surfaces by that move (measured up to
/// 5.4 mm on 1 cm deep random hull pairs); a remembered point measured from
/// them would then be off by the move times the turn since. Each anchor
/// goes where the point's normal line meets the feature its feature id
/// names on that shape (a vertex itself, an edge's point closest to the
/// line, a face's plane), when both lie on the line and give the point's
/// own depth within 1e-9 of the pair's size plus round-off; else where the
/// line enters A and leaves B, under the same test; else the midpoint
/// anchors stay. Depths at the recording pose are unchanged.
void SnapAnchorsToSurfaces(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                           const ContactManifold& manifold, ManifoldAnchors* anchors);

/// Adds the surviving points of the pair's previous manifold (`previous`,
/// its points' feature ids, with `previousAnchors` recorded from it) to the
/// fresh narrow-phase manifold `*fresh` computed at body frames `xfA`,
/// `xfB`, by the rules above; `*freshAnchors` must be RecordAnchors(*fresh,
/// xfA, xfB) and is extended with the kept points' original anchors, so a
/// kept point is carried forward from the surface points it was made of,
/// not from a midpoint that would move with each step's drift. `distance`
/// (metres, finite, > 0) is the break distance. A fresh manifold with more
/// than `maxFreshPoints` points (the World passes kPersistentFreshPoints),
/// kPersistentMaxPoints or more, none, or none that penetrates (deepest
/// depth <= 0), is left as it is.
/// Returns the number of remembered points added.
int MergePersistentPoints(const ContactManifold& previous, const ManifoldAnchors& previousAnchors,
                          const Transform& xfA, const Transform& xfB, double distance, int maxFreshPoints,
                          ContactManifold* fresh, ManifoldAnchors* freshAnchors);

}  // namespace talus
