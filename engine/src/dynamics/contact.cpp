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
  Contact contact;
  ResetContact(bodyA, bodyB, manifold, friction, restitution, &contact);
  return contact;
}

void ResetContact(int bodyA, int bodyB, const ContactManifold& manifold, double friction, double restitution,
                  Contact* contact) {
  assert(manifold.pointCount >= 0 && manifold.pointCount <= kMaxManifoldPoints);
  contact->bodyA = bodyA;
  contact->bodyB = bodyB;
  contact->manifold = manifold;
  contact->normalImpulse.fill(0.0);
  for (Vec3& impulse : contact->frictionImpulse) impulse.setZero();
  contact->friction = friction;
  contact->restitution = restitution;
  contact->persisted = false;
}

// Per pair the manifolds have at most eight points each, so the matches are a
// direct 8 x 8 search with no allocation: first by feature id, then, for the
// points still unmatched, the nearest unmatched old point within
// kWarmStartMatchDistance (the narrow phase may name the same physical point
// differently from one step to the next, e.g. when two parallel faces swap
// the roles of reference and incident face; Bullet matches by proximity
// alone for the same reason).
int CarryPairImpulses(const Contact& before, Contact& fresh) {
  int matched = 0;
  fresh.persisted = true;
  std::array<bool, kMaxManifoldPoints> used{};
  std::array<bool, kMaxManifoldPoints> found{};
  const auto take = [&](std::size_t i, std::size_t j) {
    fresh.normalImpulse[i] = before.normalImpulse[j];
    fresh.frictionImpulse[i] = before.frictionImpulse[j];
    used[j] = true;
    found[i] = true;
    ++matched;
  };
  const std::size_t freshCount = static_cast<std::size_t>(fresh.manifold.pointCount);
  const std::size_t beforeCount = static_cast<std::size_t>(before.manifold.pointCount);
  for (std::size_t i = 0; i < freshCount; ++i) {
    const std::uint32_t feature = fresh.manifold.points[i].featureId;
    for (std::size_t j = 0; j < beforeCount; ++j) {
      if (!used[j] && before.manifold.points[j].featureId == feature) {
        take(i, j);
        break;
      }
    }
  }
  constexpr double kMatch2 = kWarmStartMatchDistance * kWarmStartMatchDistance;
  for (std::size_t i = 0; i < freshCount; ++i) {
    if (found[i]) continue;
    std::size_t best = beforeCount;
    double bestDistance2 = kMatch2;
    for (std::size_t j = 0; j < beforeCount; ++j) {
      if (used[j]) continue;
      const double d2 =
          (fresh.manifold.points[i].position - before.manifold.points[j].position).squaredNorm();
      if (d2 < bestDistance2) {
        bestDistance2 = d2;
        best = j;
      }
    }
    if (best < beforeCount) take(i, best);
  }
  return matched;
}

// Both lists are sorted by pair key, so one forward walk pairs them up.
int CarryImpulses(std::span<const Contact> previous, std::span<Contact> current) {
  int matched = 0;
  std::size_t old = 0;
  for (Contact& fresh : current) {
    const std::uint64_t key = fresh.PairKey();
    while (old < previous.size() && previous[old].PairKey() < key) ++old;
    if (old == previous.size()) break;
    if (previous[old].PairKey() == key) matched += CarryPairImpulses(previous[old], fresh);
  }
  return matched;
}

}  // namespace talus
