// Bullet's pair detectors on zero-margin hull shapes. btPointCollector
// reports the normal on B pointing towards A and the point on B; the point
// on A is then pointOnB + normal * distance. btGjkEpaSolver2 reports its
// witnesses on each shape; the normal is taken from them.
#include "talus/reference/bullet_narrow_phase.h"

#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>

#include <cmath>

namespace talus::reference {

struct BulletHullShape::Impl {
  btConvexHullShape shape;
};

namespace {

btTransform ToBullet(const Transform& xf) {
  const btQuaternion q(xf.rotation.x(), xf.rotation.y(), xf.rotation.z(), xf.rotation.w());
  return btTransform(q, btVector3(xf.position.x(), xf.position.y(), xf.position.z()));
}

Vec3 FromBullet(const btVector3& v) { return {v.x(), v.y(), v.z()}; }

BulletAnswer Finish(BulletAnswer answer) {
  if (!std::isfinite(answer.signedDistance) || !answer.normal.allFinite() || !answer.point.allFinite() ||
      answer.normal.norm() == 0.0) {
    answer.ok = false;
    return answer;
  }
  answer.normal.normalize();
  answer.intersecting = answer.signedDistance < 0.0;
  return answer;
}

}  // namespace

BulletHullShape::BulletHullShape(const Hull& hull) : m_impl(std::make_unique<Impl>()) {
  for (const Vec3& v : hull.Vertices()) m_impl->shape.addPoint(btVector3(v.x(), v.y(), v.z()), false);
  m_impl->shape.recalcLocalAabb();
  m_impl->shape.setMargin(0.0);
}

BulletHullShape::~BulletHullShape() = default;

BulletAnswer BulletPairQuery(const BulletHullShape& a, const Transform& xfA, const BulletHullShape& b,
                             const Transform& xfB, BulletNarrowPhaseMethod method) {
  const btConvexHullShape& shapeA = a.Get().shape;
  const btConvexHullShape& shapeB = b.Get().shape;
  BulletAnswer answer;
  if (method == BulletNarrowPhaseMethod::GjkPairDetector) {
    btVoronoiSimplexSolver simplex;
    btGjkEpaPenetrationDepthSolver epa;
    btGjkPairDetector detector(&shapeA, &shapeB, &simplex, &epa);
    btGjkPairDetector::ClosestPointInput input;
    input.m_transformA = ToBullet(xfA);
    input.m_transformB = ToBullet(xfB);
    btPointCollector collector;
    detector.getClosestPoints(input, collector, nullptr);
    if (!collector.m_hasResult) {
      answer.ok = false;
      return answer;
    }
    answer.signedDistance = collector.m_distance;
    answer.normal = FromBullet(collector.m_normalOnBInWorld);
    const Vec3 onB = FromBullet(collector.m_pointInWorld);
    answer.point = onB + 0.5 * answer.signedDistance * answer.normal;
    return Finish(answer);
  }
  btGjkEpaSolver2::sResults results;
  const bool ok = btGjkEpaSolver2::SignedDistance(&shapeA, ToBullet(xfA), &shapeB, ToBullet(xfB),
                                                  btVector3(1.0, 0.0, 0.0), results);
  if (!ok && results.status != btGjkEpaSolver2::sResults::Penetrating &&
      results.status != btGjkEpaSolver2::sResults::Separated) {
    answer.ok = false;
    return answer;
  }
  answer.signedDistance = results.distance;
  // The witnesses fix the normal's sign: A's witness minus B's points from
  // B towards A when separated and the other way when penetrating.
  const Vec3 witnessA = FromBullet(results.witnesses[0]);
  const Vec3 witnessB = FromBullet(results.witnesses[1]);
  const Vec3 between = results.distance < 0.0 ? witnessB - witnessA : witnessA - witnessB;
  answer.normal = between.norm() > 1e-12 ? between : FromBullet(results.normal);
  answer.point = 0.5 * (FromBullet(results.witnesses[0]) + FromBullet(results.witnesses[1]));
  return Finish(answer);
}

}  // namespace talus::reference
