// Recording a manifold in the bodies' frames and rebuilding it (see
// collision/manifold_reuse.h).
#include "collision/manifold_reuse.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>

namespace talus {
namespace {

// B's pose in A's frame: rotation qA^-1 qB, B's origin qA^-1 (oB - oA).
Quat RelativeRotation(const Transform& xfA, const Transform& xfB) {
  return xfA.rotation.conjugate() * xfB.rotation;
}

// The angle (radians, in [0, pi]) of the turn from unit quaternion `from` to
// unit quaternion `to`. atan2 of the half-angle's sine and cosine stays
// accurate for the tiny angles that matter here, where acos(w) would lose
// half the digits.
double TurnAngle(const Quat& from, const Quat& to) {
  const Quat delta = to * from.conjugate();
  return 2.0 * std::atan2(delta.vec().norm(), std::abs(delta.w()));
}

}  // namespace

ManifoldAnchors RecordAnchors(const ContactManifold& manifold, const Transform& xfA, const Transform& xfB) {
  assert(manifold.pointCount >= 0 && manifold.pointCount <= kMaxManifoldPoints);
  ManifoldAnchors anchors;
  anchors.recorded = true;
  anchors.pointCount = manifold.pointCount;
  anchors.relativeRotation = RelativeRotation(xfA, xfB);
  anchors.relativePosition = xfA.ApplyInverse(xfB.position);
  anchors.localNormal = xfA.RotateInverse(manifold.normal);
  // The point is midway between the surfaces and depth = (pB - pA) . n, so
  // A's surface point lies half the depth back along n and B's half forward.
  for (std::size_t i = 0; i < static_cast<std::size_t>(manifold.pointCount); ++i) {
    const ContactPoint& point = manifold.points[i];
    const Vec3 half = 0.5 * point.depth * manifold.normal;
    anchors.localPointA[i] = xfA.ApplyInverse(point.position - half);
    anchors.localPointB[i] = xfB.ApplyInverse(point.position + half);
  }
  return anchors;
}

// A point p of B sits at R p + t in A's frame. Since the recording R became
// R' and t became t', so the point moved by (R' - R) p + (t' - t), whose
// length is at most theta |p| + |t' - t| with theta the angle of R' R^-1.
// Seen from B, A's origin sits at -R^-1 t; the same argument with A's
// radius gives a second bound, and both hold, so the smaller one does.
double RelativeMotionBound(const ManifoldAnchors& anchors, const Transform& xfA, const Transform& xfB,
                           double radiusA, double radiusB) {
  if (!anchors.recorded) return std::numeric_limits<double>::infinity();
  const Quat rotation = RelativeRotation(xfA, xfB);
  const Vec3 position = xfA.ApplyInverse(xfB.position);
  const double theta = TurnAngle(anchors.relativeRotation, rotation);
  const double moveB = (position - anchors.relativePosition).norm() + theta * radiusB;
  const Vec3 originA = -(rotation.conjugate() * position);
  const Vec3 recordedOriginA = -(anchors.relativeRotation.conjugate() * anchors.relativePosition);
  const double moveA = (originA - recordedOriginA).norm() + theta * radiusA;
  return std::min(moveA, moveB);
}

void RebuildManifold(const ManifoldAnchors& anchors, const Transform& xfA, const Transform& xfB,
                     ContactManifold* manifold) {
  assert(anchors.recorded && anchors.pointCount == manifold->pointCount);
  const Vec3 normal = xfA.Rotate(anchors.localNormal);
  manifold->normal = normal;
  double deepest = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < static_cast<std::size_t>(anchors.pointCount); ++i) {
    const Vec3 onA = xfA.Apply(anchors.localPointA[i]);
    const Vec3 onB = xfB.Apply(anchors.localPointB[i]);
    ContactPoint& point = manifold->points[i];
    point.position = 0.5 * (onA + onB);
    point.depth = normal.dot(onB - onA);
    deepest = std::max(deepest, point.depth);
  }
  // The SAT's least overlap is not re-measured; the deepest point stands in
  // for it (the solver reads only the points).
  if (anchors.pointCount > 0) manifold->depth = deepest;
}

}  // namespace talus
