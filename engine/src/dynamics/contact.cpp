// Material mixing and the feature-id matching behind warm starting.
#include "dynamics/contact.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace talus {

double MixFriction(double a, double b, FrictionCombine rule) {
  switch (rule) {
    case FrictionCombine::GeometricMean:
      return std::sqrt(a * b);
    case FrictionCombine::Product:
      return a * b;
    case FrictionCombine::Min:
      return std::min(a, b);
    case FrictionCombine::Max:
      return std::max(a, b);
    case FrictionCombine::Average:
      return 0.5 * (a + b);
  }
  assert(false && "unknown friction combine rule");
  return 0.0;
}

double MixRestitution(double a, double b, RestitutionCombine rule) {
  switch (rule) {
    case RestitutionCombine::Max:
      return std::max(a, b);
    case RestitutionCombine::Product:
      return a * b;
    case RestitutionCombine::Min:
      return std::min(a, b);
    case RestitutionCombine::Average:
      return 0.5 * (a + b);
  }
  assert(false && "unknown restitution combine rule");
  return 0.0;
}

Contact MakeContact(int bodyA, int bodyB, const ContactManifold& manifold, double friction,
                    double restitution) {
  assert(manifold.pointCount >= 0 && manifold.pointCount <= kMaxManifoldPoints);
  Contact contact;
  contact.bodyA = bodyA;
  contact.bodyB = bodyB;
  contact.manifold = manifold;
  contact.friction = friction;
  contact.restitution = restitution;
  for (Vec3& impulse : contact.frictionImpulse) impulse.setZero();
  return contact;
}

// Both lists are sorted by pair key, so one forward walk pairs them up; per
// pair the manifolds have at most eight points each, so the feature match is
// a direct 8 x 8 search with no allocation.
int CarryImpulses(std::span<const Contact> previous, std::span<Contact> current) {
  int matched = 0;
  std::size_t old = 0;
  for (Contact& fresh : current) {
    const std::uint64_t key = fresh.PairKey();
    while (old < previous.size() && previous[old].PairKey() < key) ++old;
    if (old == previous.size()) break;
    const Contact& before = previous[old];
    if (before.PairKey() != key) continue;
    for (int i = 0; i < fresh.manifold.pointCount; ++i) {
      const std::uint32_t feature = fresh.manifold.points[static_cast<std::size_t>(i)].featureId;
      for (int j = 0; j < before.manifold.pointCount; ++j) {
        if (before.manifold.points[static_cast<std::size_t>(j)].featureId != feature) continue;
        fresh.normalImpulse[static_cast<std::size_t>(i)] = before.normalImpulse[static_cast<std::size_t>(j)];
        fresh.frictionImpulse[static_cast<std::size_t>(i)] =
            before.frictionImpulse[static_cast<std::size_t>(j)];
        ++matched;
        break;
      }
    }
  }
  return matched;
}

}  // namespace talus
