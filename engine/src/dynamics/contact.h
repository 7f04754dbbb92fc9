// Contact: the record of one touching pair that the step keeps between
// steps.
//
// A Contact holds the pair's manifold from the narrow phase plus what must
// survive to the next step for warm starting: the accumulated normal and
// friction impulses of each point, keyed by the point's feature id, and the
// pair's mixed friction and restitution. The solver's per-step rows
// (dynamics/contact_row_set.h) are rebuilt from Contacts every step; only
// impulses flow back. Keeping the two apart keeps the rows small and dense
// and lets the warm start survive any change of manifold point order.
//
// The manifold written down in the two bodies' frames (ManifoldAnchors,
// collision/manifold_reuse.h), which only the narrow phase of the same pair
// reads one step later (manifold reuse and persistent points), is not part
// of the Contact: the world keeps it in a list of its own beside the
// contacts (world/world_data.h). Every stage that walks the contacts
// (warm-start matching, row preparation, storing impulses, islands, the
// contact query) then reads 648 bytes a pair instead of 1,136, and a pair
// whose manifold is rebuilt from its anchors copies them once, from last
// step's list to this step's, instead of through the narrow phase's output.
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

  /// The order key of the pair (the free PairKey of its two bodies).
  [[nodiscard]] std::uint64_t PairKey() const { return talus::PairKey(bodyA, bodyB); }
};

// Byte budgets (x86-64, 8-byte doubles), checked so that a field added to a
// record every stage copies or walks is a decision, not an accident:
//   Contact         648 = 8 (body indices) + 360 (manifold: 40 header and
//                   8 points of 40) + 64 (normal impulses) + 192 (friction
//                   impulse vectors) + 16 (friction, restitution) + 8
//                   (persisted, padded)
//   ManifoldAnchors 480 = 8 (recorded, count) + 8 (padding: Eigen's
//                   quaternion is 16-byte aligned) + 32 (rotation) + 48
//                   (position, normal) + 384 (two anchors of 8 points)
// The anchors were part of the Contact until the split (1,136 bytes with
// the padding in front of them).
static_assert(sizeof(ContactManifold) <= 360, "ContactManifold grew past its 360-byte budget");
static_assert(sizeof(Contact) <= 648, "Contact grew past its 648-byte budget");
static_assert(sizeof(ManifoldAnchors) <= 480, "ManifoldAnchors grew past its 480-byte budget");

/// The pair's friction from each body's coefficient (both >= 0).
double MixFriction(double a, double b, FrictionCombine rule);
/// The pair's restitution from each body's coefficient (both in [0, 1]).
double MixRestitution(double a, double b, RestitutionCombine rule);

/// A fresh contact for a manifold, impulses zero.
Contact MakeContact(int bodyA, int bodyB, const ContactManifold& manifold, double friction,
                    double restitution);
/// Makes `*contact` a fresh contact for a manifold, impulses zero, in place:
/// the same record MakeContact returns, without a temporary copy.
void ResetContact(int bodyA, int bodyB, const ContactManifold& manifold, double friction, double restitution,
                  Contact* contact);

/// How far (metres) a contact point may be from an old point of the same
/// pair with a different feature id and still inherit its impulses. 1 cm:
/// well above the distance a resting or slowly sliding contact moves in one
/// step, well below the spacing of the points of a manifold.
inline constexpr double kWarmStartMatchDistance = 0.01;

/// Warm starting of one pair: copies into `fresh` the accumulated impulses
/// of each point from the point of `before` (last step's contact of the
/// same pair) with the same feature id or, failing that, the nearest
/// unclaimed old point within kWarmStartMatchDistance. Each old point is
/// used once. Marks `fresh` persisted. Returns the points that found their
/// old impulses. A manifold matched against itself (same points in the same
/// order, as a kept or rebuilt manifold is) takes every point's own
/// impulses back.
int CarryPairImpulses(const Contact& before, Contact& fresh);

/// Warm starting: for every contact in `current` whose pair is also in
/// `previous`, copies the accumulated impulses of each point from the old
/// point with the same feature id or, failing that, the nearest unclaimed
/// old point within kWarmStartMatchDistance. Each old point is used once.
/// Both lists must be sorted by PairKey. Marks every contact whose pair is
/// in `previous` as persisted. Returns the number of points that found
/// their old impulses.
int CarryImpulses(std::span<const Contact> previous, std::span<Contact> current);

}  // namespace talus
