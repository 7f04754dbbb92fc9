// ManifoldAnchors: a polyhedron pair's contact manifold written down in the
// two bodies' own frames, so that while the pair's relative pose stays close
// to the pose the narrow phase computed it at, the manifold can be rebuilt
// from the current poses without the SAT and the clipping. This is the
// body-pair manifold cache of Jolt Physics (PhysicsSettings::
// mBodyPairCacheMaxDeltaPositionSq and mBodyPairCacheCosMaxDeltaRotationDiv2,
// J. Rouwe); the threshold here is a single distance, see
// RelativeMotionBound.
//
// What is stored, per point: A's surface point in A's body frame and B's in
// B's (the manifold point is midway between the surfaces, so they are
// position -+ depth/2 along the normal: the normal points from B towards A
// and depth = (pB - pA) . n is positive when penetrating); the normal in
// A's frame; and the relative pose of B in A's frame at which all of it was
// recorded. Feature ids and the point count stay in the manifold that is
// rebuilt, so warm starting matches the points exactly as before.
//
// Invariants: anchors are recorded only from a fresh narrow-phase manifold,
// never from a rebuilt one, so the reference pose is always one the narrow
// phase saw and reuse errors cannot accumulate from step to step; `recorded`
// is false until RecordAnchors ran; pointCount equals the recorded
// manifold's.
//
// Accuracy (face contacts, the clipped generator): if no point of B moved
// by more than delta relative to A (or of A relative to B) since the
// recording, with relative rotation theta, a rebuilt point's depth differs
// from the fresh narrow phase's point of the same feature id by at most
//     theta (|depth| + delta)   the normal kept in A's frame while the
//                               reference face is B's,
//   + delta tan(phi)            a reference corner under an incident face
//                               tilted by phi to the reference face,
//   + L sin(phi)                an incident edge cut by a side plane (the
//                               cut slides along the edge; L, the part of
//                               the edge over the reference face, is at most
//                               the smaller body's diameter plus delta),
// and an incident vertex under a reference face of A is exact. Resting
// faces start parallel, so phi <= theta, and theta r <= delta for the body
// whose bound was used, so a millimetre of reuse distance moves a depth by
// a few millimetres at the very most (tests/collision/
// manifold_reuse_test.cpp checks the bound on random perturbations of
// resting boxes and hulls).
#pragma once

#include <array>

#include "collision/contact_manifold.h"
#include "talus/math.h"
#include "talus/transform.h"

namespace talus {

// The quaternion leads and the flags trail: under AVX (Eigen aligns a Quat
// to 32 bytes there) flags in front cost a 32-byte slot and the record
// grew from 480 to 512 bytes.
struct ManifoldAnchors {
  /// B's rotation relative to A (qA^-1 qB) when recorded.
  Quat relativeRotation = Quat::Identity();
  /// B's frame origin in A's frame when recorded, metres.
  Vec3 relativePosition = Vec3::Zero();
  /// The manifold normal (from B towards A) in A's frame.
  Vec3 localNormal = Vec3::Zero();
  /// A's surface point of each contact point, A's frame, metres.
  std::array<Vec3, kMaxManifoldPoints> localPointA{};
  /// B's surface point of each contact point, B's frame, metres.
  std::array<Vec3, kMaxManifoldPoints> localPointB{};
  int pointCount = 0;     ///< points of the recorded manifold
  bool recorded = false;  ///< false: nothing to rebuild from
};

/// Writes `manifold`, computed by the narrow phase at body frames `xfA` and
/// `xfB`, down in the bodies' frames.
ManifoldAnchors RecordAnchors(const ContactManifold& manifold, const Transform& xfA, const Transform& xfB);

/// An upper bound, metres, on how far any point of one body has moved
/// relative to the other since `anchors` were recorded: |dt| + theta r, with
/// dt the change of B's origin in A's frame, theta the angle of the change
/// of relative rotation and r = `radiusB` the radius of a sphere about B's
/// frame origin holding B (|R' p - R p| <= theta |p| for a turn by theta);
/// the same with A and B swapped; the smaller of the two. Infinite when
/// nothing was recorded.
double RelativeMotionBound(const ManifoldAnchors& anchors, const Transform& xfA, const Transform& xfB,
                           double radiusA, double radiusB);

/// Rebuilds the manifold the anchors were recorded from at the current body
/// frames: normal from A's frame, each point midway between its two anchors,
/// its depth (pB - pA) . n; `manifold->depth` becomes the deepest point's.
/// Feature ids and the point count of `*manifold` (the recorded manifold)
/// are kept.
void RebuildManifold(const ManifoldAnchors& anchors, const Transform& xfA, const Transform& xfB,
                     ContactManifold* manifold);

}  // namespace talus
