// btDbvtBroadphase driven the way btCollisionWorld::updateAabbs and
// performDiscreteCollisionDetection drive it: setAabb on every proxy, then
// calculateOverlappingPairs with a collision dispatcher (needed to release
// pairs that stop overlapping).
#include "talus/reference/bullet_broad_phase.h"

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>

#include <cassert>
#include <vector>

namespace talus::reference {

struct BulletDbvtBroadPhase::Impl {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadPhase;
  std::vector<btBroadphaseProxy*> proxies;
};

namespace {

void Box(const Sphere& s, btVector3* lo, btVector3* hi) {
  *lo = btVector3(s.center.x() - s.radius, s.center.y() - s.radius, s.center.z() - s.radius);
  *hi = btVector3(s.center.x() + s.radius, s.center.y() + s.radius, s.center.z() + s.radius);
}

}  // namespace

BulletDbvtBroadPhase::BulletDbvtBroadPhase(std::span<const Sphere> spheres, std::span<const bool> isStatic)
    : m_impl(std::make_unique<Impl>()) {
  assert(spheres.size() == isStatic.size());
  m_impl->proxies.reserve(spheres.size());
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    btVector3 lo;
    btVector3 hi;
    Box(spheres[i], &lo, &hi);
    const int group = isStatic[i] ? btBroadphaseProxy::StaticFilter : btBroadphaseProxy::DefaultFilter;
    const int mask = isStatic[i] ? btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter
                                 : btBroadphaseProxy::AllFilter;
    m_impl->proxies.push_back(m_impl->broadPhase.createProxy(lo, hi, BOX_SHAPE_PROXYTYPE, nullptr, group,
                                                             mask, &m_impl->dispatcher));
  }
}

BulletDbvtBroadPhase::~BulletDbvtBroadPhase() {
  for (btBroadphaseProxy* proxy : m_impl->proxies)
    m_impl->broadPhase.destroyProxy(proxy, &m_impl->dispatcher);
}

std::int64_t BulletDbvtBroadPhase::Step(std::span<const Sphere> spheres) {
  assert(spheres.size() == m_impl->proxies.size());
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    btVector3 lo;
    btVector3 hi;
    Box(spheres[i], &lo, &hi);
    m_impl->broadPhase.setAabb(m_impl->proxies[i], lo, hi, &m_impl->dispatcher);
  }
  m_impl->broadPhase.calculateOverlappingPairs(&m_impl->dispatcher);
  return m_impl->broadPhase.getOverlappingPairCache()->getNumOverlappingPairs();
}

}  // namespace talus::reference
