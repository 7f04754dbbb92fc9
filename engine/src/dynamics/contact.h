// Contact: the persistent record of one touching pair between steps.
//
// A Contact holds the pair's manifold from the narrow phase plus what must
// survive to the next step: the accumulated normal and friction impulses of
// each point, keyed by the point's feature id, and the pair's mixed
// friction and restitution, and the manifold written down in the two
// bodies' frames (collision/manifold_reuse.h) so that a pair that barely
// moved can skip the narrow phase. The solver's per-step rows (dynamics/
// contact_solver.h) are rebuilt from Contacts every step; only impulses flow
// back. Keeping the two apart keeps the rows small and dense and lets the
// warm start survive any change of manifold point order.
//
// Invariants: bodyA < bodyB is not required, but a pair appears once; the
// normal points from B towards A; contact lists handed between steps are
// sorted by PairKey so matching is a merge walk with a deterministic result.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "collision/contact_manifold.h"
#include "collision/manifold_reuse.h"
#include "talus/math.h"
#include "talus/world_settings.h"

namespace talus {

/// The order key of the body pair (a, b): a's index in the high half, b's
/// in the low, so sorting by it sorts by (a, b), the broad phase's order.
inline std::uint64_t PairKey(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

struct Contact {
  int bodyA = -1;  ///< body index of A (the normal points towards A)
  int bodyB = -1;  ///< body index of B
  ContactManifold manifold{};
  /// Accumulated normal impulse per manifold point, N s, >= 0.
  std::array<double, kMaxManifoldPoints> normalImpulse{};
  /// Accumulated friction impulse per point as a world vector in the contact
  /// plane, N s. Stored as a vector, not per tangent row, so the warm start
  /// survives a change of tangent basis between steps.
  std::array<Vec3, kMaxManifoldPoints> frictionImpulse{};
  double friction = 0.0;     ///< the pair's mixed Coulomb coefficient
  double restitution = 0.0;  ///< the pair's mixed restitution
  /// Whether the pair was touching last step too (set by CarryImpulses); a
  /// new pair has no impulses to start from and gets extra solver sweeps.
  bool persisted = false;
  /// The manifold in the bodies' frames, as the narrow phase last computed
  /// it, for reuse while the pair barely moves (NarrowPhaseSettings::
  /// reuseDistance); not recorded when reuse is off.
  ManifoldAnchors anchors{};

  /// The order key of the pair (the free PairKey of its two bodies).
  [[nodiscard]] std::uint64_t PairKey() const { return talus::PairKey(bodyA, bodyB); }
};

/// The pair's friction from each body's coefficient (both >= 0).
double MixFriction(double a, double b, FrictionCombine rule);
/// The pair's restitution from each body's coefficient (both in [0, 1]).
double MixRestitution(double a, double b, RestitutionCombine rule);

/// A fresh contact for a manifold, impulses zero.
Contact MakeContact(int bodyA, int bodyB, const ContactManifold& manifold, double friction,
                    double restitution);

/// How far (metres) a contact point may be from an old point of the same
/// pair with a different feature id and still inherit its impulses. 1 cm:
/// well above the distance a resting or slowly sliding contact moves in one
/// step, well below the spacing of the points of a manifold.
inline constexpr double kWarmStartMatchDistance = 0.01;

/// Warm starting: for every contact in `current` whose pair is also in
/// `previous`, copies the accumulated impulses of each point from the old
/// point with the same feature id or, failing that, the nearest unclaimed
/// old point within kWarmStartMatchDistance. Each old point is used once.
/// Both lists must be sorted by PairKey. Marks every contact whose pair is
/// in `previous` as persisted. Returns the number of points that found
/// their old impulses.
int CarryImpulses(std::span<const Contact> previous, std::span<Contact> current);

}  // namespace talus
