// WideContactSolver: the contact rows of one step, coloured and packed four
// pairs to a bundle, solved a bundle at a time with SIMD lanes
// (MethodSettings::contactOrder = ByColour).
//
// The algorithm per pair is the scalar solver's (dynamics/sequential_impulse_sweeps.h:
// the same rows, clamps, block solve with its row-by-row fallback, friction
// bounded by the current normal impulse); what changes is the order in
// which pairs are visited. The pairs are coloured (dynamics/
// constraint_colouring.h) so that no two pairs of a colour share a body
// contacts can move; a colour's pairs are then independent within a pass,
// and four of them are solved at once, one per lane (pair p of the colour
// in lane p % 4 of bundle p / 4). A sweep is: for each colour, its normal
// rows; the overflow pairs' normal rows one by one; then likewise the
// friction rows (all normals before all friction, as the scalar sweep).
//
// Threads. `SolveNormalRange(colour, begin, end)` and its friction and warm
// start siblings solve bundles [begin, end) of one colour. Two calls on
// disjoint ranges of the same colour touch disjoint rows and disjoint
// movable bodies (they only read immovable ones, which no call writes), so
// they may run concurrently; and since a bundle's result depends on its own
// rows and bodies alone, any split of a colour into ranges gives
// bit-identical results (tested). Colours must run one after the other,
// and the overflow pairs after all colours (ColouredContactDispatch does that,
// dynamics/coloured_contact_dispatch.h).
//
// Layout (structure of arrays per bundle, 32-byte aligned lanes): a bundle
// header (normals, tangents, inverse masses, friction, inverse inertias,
// the block inverses, body indices), then `points` wide points (arms,
// masses, target, impulses), each a run of four-lane arrays.
// Empty lanes and the points past a lane's own count are zero rows: zero
// mass and Jacobian, so they add exactly zero and keep zero impulse.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "dynamics/constraint_colouring.h"
#include "dynamics/contact_rows.h"
#include "dynamics/solver_body.h"
#include "jobs/job_pool.h"

namespace talus {

class WideContactSolver {
 public:
  /// Most points of a pair the bundles hold; pairs with more (manifolds of
  /// up to 8 points when not reduced) are solved in the overflow colour.
  static constexpr int kMaxBundlePoints = 4;
  /// Pairs per bundle: the lanes of one SIMD register of doubles (AVX2).
  static constexpr int kLanes = 4;

  /// Colours `pairs` and packs their rows (copies; `normals`, `frictions`
  /// and `blocks` are the scalar solver's arrays the pairs index). Keeps
  /// capacity between steps. The colouring and the layout are serial; the
  /// packing runs bundle by bundle through `runner` (any cut, the same bits).
  void Build(std::span<const PairRows> pairs, std::span<const NormalRow> normals,
             std::span<const FrictionRow> frictions, std::span<const PointCold> cold,
             std::span<const Eigen::Matrix4d> blocks, const SolverBodies& bodies,
             const PhaseRunner& runner = nullptr);

  /// Colours in use, 0 .. ColourCount() - 1 (empty colours are dropped).
  [[nodiscard]] int ColourCount() const { return static_cast<int>(m_colourStart.size()) - 1; }
  /// Bundles (of up to four pairs) in `colour`.
  [[nodiscard]] int BundleCount(int colour) const {
    return m_colourStart[static_cast<std::size_t>(colour) + 1] -
           m_colourStart[static_cast<std::size_t>(colour)];
  }
  /// Pairs (indices into the pairs handed to Build) solved one by one after
  /// the colours, in pair order.
  [[nodiscard]] std::span<const int> OverflowPairs() const { return m_overflow; }

  /// Applies the loaded impulses of bundles [begin, end) of `colour`.
  void WarmStartRange(SolverBodies& bodies, int colour, int begin, int end) const;
  /// One pass over the normal rows of bundles [begin, end) of `colour`.
  /// With `track`, returns the largest velocity change (|dlambda| / m, m/s)
  /// of a row of a new pair, else 0.
  double SolveNormalRange(SolverBodies& bodies, int colour, int begin, int end, bool track);
  /// The same for the friction rows.
  double SolveFrictionRange(SolverBodies& bodies, int colour, int begin, int end, bool track);

  /// Writes the accumulated impulses back into the scalar rows (bundle by
  /// bundle through `runner`).
  void Unpack(std::span<const PairRows> pairs, std::span<NormalRow> normals, std::span<FrictionRow> frictions,
              const PhaseRunner& runner = nullptr) const;

  /// Four lanes of one number.
  struct alignas(32) Lanes {
    double v[4] = {0.0, 0.0, 0.0, 0.0};
  };
  /// One point of four pairs: the arms, the rows' effective masses, the
  /// normal target and the accumulated impulses. The Jacobians' angular
  /// parts r x d and their images I^-1 (r x d) are formed in the sweep
  /// from the arms and the bundle's inverse inertias, with the scalar
  /// Prepare's operations in its order (so the same bits): the sweeps are
  /// bound by memory traffic, and this is 13 lane arrays per point where
  /// the precomputed rows took 48.
  struct WidePoint {
    Lanes armA[3], armB[3];
    Lanes normalMass, target, normalImpulse;
    Lanes tangentMass[2], tangentImpulse[2];
  };
  struct Bundle {
    Lanes normal[3], tangent[2][3];
    Lanes invMassA, invMassB, friction;
    Lanes invInertiaA[9], invInertiaB[9];  ///< world inverse inertia, row-major; zero when immovable
    Lanes block[16];                       ///< K+ row-major, zero in lanes without a block
    int bodyA[4] = {-1, -1, -1, -1}, bodyB[4] = {-1, -1, -1, -1};  ///< solver bodies, -1 empty
    int pair[4] = {-1, -1, -1, -1};  ///< index of the pair in each lane, -1 empty
    int firstPoint = 0;
    int points = 0;             ///< most points of a lane
    unsigned blockBits = 0;     ///< lanes solved as a block first
    unsigned frictionBits = 0;  ///< lanes with friction rows
    unsigned newBits = 0;       ///< lanes of new pairs (the extra sweeps track their rows)
    unsigned storeBitsA = 0;    ///< lanes whose A contacts can move (written back)
    unsigned storeBitsB = 0;
  };
  // The byte budget of the hot records. A wide point is 13 four-lane arrays,
  // 416 bytes: 104 bytes per pair's point for its normal and two friction
  // rows, against 120 + 2 x 112 = 344 bytes of scalar rows. A bundle header
  // is 46 four-lane arrays (normal, tangents, inverse masses, friction, two
  // inverse inertias, the 4x4 block inverse: 1,472 bytes) plus 80 bytes of
  // indices and flags: 388 bytes per pair against the scalar PairRows' 136
  // plus its 128-byte block inverse. Growing either is a choice to make on
  // purpose: the sweeps stream these every pass.
  static_assert(sizeof(WidePoint) == 13 * 32, "wide point: 13 lanes of 4 doubles");
  static_assert(sizeof(Bundle) <= 46 * 32 + 96, "bundle header: 46 lane arrays plus indices and flags");

 private:
  /// Where Build puts a bundle: its pairs are m_order[firstOrder ..
  /// firstOrder + lanes), its points m_points[firstPoint .. + points).
  struct BundleLayout {
    int firstOrder = 0;
    int lanes = 0;
    int firstPoint = 0;
    int points = 0;
  };

  /// Where each colour's pairs start in m_order (a running sum of the
  /// counts): colour c's are [starts[c], starts[c + 1]), the overflow
  /// colour's from starts[kOverflowColour].
  using ColourStarts = std::array<int, kColourCount + 2>;
  /// The arrays Build packs from (the scalar solver's).
  struct RowsToPack {
    std::span<const PairRows> pairs;
    std::span<const NormalRow> normals;
    std::span<const FrictionRow> frictions;
    std::span<const PointCold> cold;
    std::span<const Eigen::Matrix4d> blocks;
    const SolverBodies& bodies;
  };

  /// Colours the pairs (m_colourOf).
  void Colour(std::span<const PairRows> pairs, const SolverBodies& bodies);
  /// The pairs grouped by colour into m_order and the overflow pairs listed.
  ColourStarts OrderByColour(std::size_t pairCount);
  /// Each bundle's pairs and points (m_layout, m_colourStart); returns the wide points.
  int LayOutBundles(std::span<const PairRows> pairs, const ColourStarts& starts);
  void PackBundle(int b, const RowsToPack& rows);
  void PackLane(Bundle& bundle, int lane, int p, const RowsToPack& rows);
  void UnpackBundle(const Bundle& bundle, std::span<const PairRows> pairs, std::span<NormalRow> normals,
                    std::span<FrictionRow> frictions) const;

  std::vector<Bundle> m_bundles;
  std::vector<WidePoint> m_points;
  std::vector<int> m_colourStart;  ///< bundles of colour c: [m_colourStart[c], m_colourStart[c + 1])
  std::vector<int> m_overflow;
  // Scratch kept between steps.
  std::vector<ColourInput> m_inputs;
  std::vector<int> m_colourOf;
  std::vector<std::uint32_t> m_used;
  std::vector<int> m_order;
  std::vector<BundleLayout> m_layout;
};

}  // namespace talus
