// WideContactSolver: colouring the pairs and packing their rows into
// four-lane bundles (Build), and the impulses written back (Unpack). The
// SIMD passes are in wide_contact_kernels.cpp, the one file compiled with
// the build's SIMD flags, so that no Eigen arithmetic here (or in the
// scalar reference solver) changes with them.
#include "dynamics/wide_contact_solver.h"

#include <algorithm>
#include <cassert>

#include "dynamics/constraint_colouring.h"

namespace talus {
namespace {

// Bundles per chunk of the packing (a bundle is a few hundred nanoseconds).
constexpr int kPackBundleGrain = 16;

void Put(WideContactSolver::Lanes* xyz, int lane, const Vec3& value) {
  for (int k = 0; k < 3; ++k) xyz[k].v[lane] = value[k];
}

}  // namespace

// Colouring and layout are serial (the pair order every bundle's bits
// follow); the packing runs bundle by bundle on `runner`'s threads.
void WideContactSolver::Build(std::span<const PairRows> pairs, std::span<const NormalRow> normals,
                              std::span<const FrictionRow> frictions, std::span<const PointCold> cold,
                              std::span<const Eigen::Matrix4d> blocks, const SolverBodies& bodies,
                              const PhaseRunner& runner) {
  Colour(pairs, bodies);
  const ColourStarts starts = OrderByColour(pairs.size());
  const int points = LayOutBundles(pairs, starts);
  // Capacity is kept; every bundle and point is overwritten whole below.
  m_bundles.resize(m_layout.size());
  m_points.resize(static_cast<std::size_t>(points));
  const RowsToPack rows{pairs, normals, frictions, cold, blocks, bodies};
  const JobPhase phase{.count = static_cast<int>(m_layout.size()), .grain = kPackBundleGrain};
  RunPhasesWith(runner, std::span<const JobPhase>(&phase, 1), [&](int, int begin, int end) {
    for (int b = begin; b < end; ++b) PackBundle(b, rows);
  });
}

void WideContactSolver::Colour(std::span<const PairRows> pairs, const SolverBodies& bodies) {
  m_inputs.clear();
  for (const PairRows& pair : pairs) {
    m_inputs.push_back({.bodyA = pair.bodyA,
                        .bodyB = pair.bodyB,
                        .movesA = bodies.Moves(pair.bodyA),
                        .movesB = bodies.Moves(pair.bodyB),
                        .eligible = pair.pointCount <= kMaxBundlePoints});
  }
  ColourPairs(m_inputs, bodies.Count(), m_colourOf, m_used);
}

// Pairs grouped by colour, pair order within a colour (a counting sort);
// the overflow colour's pairs listed apart.
WideContactSolver::ColourStarts WideContactSolver::OrderByColour(std::size_t pairCount) {
  int counts[kColourCount + 1] = {};
  for (const int colour : m_colourOf) ++counts[colour];
  ColourStarts starts{};
  for (int c = 0; c <= kColourCount; ++c) starts[c + 1] = starts[c] + counts[c];
  m_order.resize(pairCount);
  int next[kColourCount + 1];
  for (int c = 0; c <= kColourCount; ++c) next[c] = starts[c];
  for (std::size_t p = 0; p < pairCount; ++p)
    m_order[static_cast<std::size_t>(next[m_colourOf[p]]++)] = static_cast<int>(p);
  m_overflow.clear();
  for (int i = starts[kOverflowColour]; i < starts[kOverflowColour + 1]; ++i) {
    m_overflow.push_back(m_order[static_cast<std::size_t>(i)]);
  }
  return starts;
}

// Each bundle's first pair (into m_order), lanes and first wide point (a
// running sum of the bundles' most points); empty colours are dropped.
// Returns the wide points in all.
int WideContactSolver::LayOutBundles(std::span<const PairRows> pairs, const ColourStarts& starts) {
  m_layout.clear();
  m_colourStart.clear();
  m_colourStart.push_back(0);
  int points = 0;
  for (int c = 0; c < kColourCount; ++c) {
    if (starts[c] == starts[c + 1]) continue;
    for (int first = starts[c]; first < starts[c + 1]; first += kLanes) {
      const int lanesUsed = std::min(kLanes, starts[c + 1] - first);
      int most = 0;
      for (int lane = 0; lane < lanesUsed; ++lane) {
        most = std::max(
            most,
            pairs[static_cast<std::size_t>(m_order[static_cast<std::size_t>(first + lane)])].pointCount);
      }
      m_layout.push_back({.firstOrder = first, .lanes = lanesUsed, .firstPoint = points, .points = most});
      points += most;
    }
    m_colourStart.push_back(static_cast<int>(m_layout.size()));
  }
  return points;
}

// Bundle `b` into its own header and points (any thread): every lane of
// its layout, the rest zero.
void WideContactSolver::PackBundle(int b, const RowsToPack& rows) {
  const BundleLayout& layout = m_layout[static_cast<std::size_t>(b)];
  Bundle& bundle = m_bundles[static_cast<std::size_t>(b)];
  bundle = Bundle{};
  bundle.firstPoint = layout.firstPoint;
  bundle.points = layout.points;
  for (int i = 0; i < layout.points; ++i) m_points[static_cast<std::size_t>(layout.firstPoint + i)] = {};
  for (int lane = 0; lane < layout.lanes; ++lane) {
    PackLane(bundle, lane, m_order[static_cast<std::size_t>(layout.firstOrder + lane)], rows);
  }
}

// Pair `p`'s header into `lane` of `bundle`, and its points' rows into the
// bundle's wide points.
void WideContactSolver::PackLane(Bundle& bundle, int lane, int p, const RowsToPack& rows) {
  const PairRows& pair = rows.pairs[static_cast<std::size_t>(p)];
  bundle.pair[lane] = p;
  bundle.bodyA[lane] = pair.bodyA;
  bundle.bodyB[lane] = pair.bodyB;
  if (rows.bodies.Moves(pair.bodyA)) bundle.storeBitsA |= 1u << lane;
  if (rows.bodies.Moves(pair.bodyB)) bundle.storeBitsB |= 1u << lane;
  if (pair.hasFriction) bundle.frictionBits |= 1u << lane;
  if (!pair.persisted) bundle.newBits |= 1u << lane;
  Put(bundle.normal, lane, pair.normal);
  Put(bundle.tangent[0], lane, pair.tangent[0]);
  Put(bundle.tangent[1], lane, pair.tangent[1]);
  bundle.invMassA.v[lane] = pair.invMassA;
  bundle.invMassB.v[lane] = pair.invMassB;
  bundle.friction.v[lane] = pair.friction;
  const Mat3& inertiaA = rows.bodies.InvInertia(pair.bodyA);
  const Mat3& inertiaB = rows.bodies.InvInertia(pair.bodyB);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      bundle.invInertiaA[3 * i + j].v[lane] = inertiaA(i, j);
      bundle.invInertiaB[3 * i + j].v[lane] = inertiaB(i, j);
    }
  }
  if (pair.block >= 0) {
    bundle.blockBits |= 1u << lane;
    const Eigen::Matrix4d& k = rows.blocks[static_cast<std::size_t>(pair.block)];
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) bundle.block[4 * i + j].v[lane] = k(i, j);
    }
  }
  for (int i = 0; i < pair.pointCount; ++i) {
    const std::size_t point = static_cast<std::size_t>(pair.firstPoint + i);
    const NormalRow& row = rows.normals[point];
    WidePoint& wide = m_points[static_cast<std::size_t>(bundle.firstPoint + i)];
    Put(wide.armA, lane, rows.cold[point].armA);
    Put(wide.armB, lane, rows.cold[point].armB);
    wide.normalMass.v[lane] = row.mass;
    wide.target.v[lane] = row.target;
    wide.normalImpulse.v[lane] = row.impulse;
    if (!pair.hasFriction) continue;
    for (int k = 0; k < 2; ++k) {
      const FrictionRow& f = rows.frictions[static_cast<std::size_t>(pair.firstFriction + 2 * i + k)];
      wide.tangentMass[k].v[lane] = f.mass;
      wide.tangentImpulse[k].v[lane] = f.impulse;
    }
  }
}

void WideContactSolver::Unpack(std::span<const PairRows> pairs, std::span<NormalRow> normals,
                               std::span<FrictionRow> frictions, const PhaseRunner& runner) const {
  const JobPhase phase{.count = static_cast<int>(m_bundles.size()), .grain = kPackBundleGrain};
  RunPhasesWith(runner, std::span<const JobPhase>(&phase, 1), [&](int, int begin, int end) {
    for (int b = begin; b < end; ++b)
      UnpackBundle(m_bundles[static_cast<std::size_t>(b)], pairs, normals, frictions);
  });
}

void WideContactSolver::UnpackBundle(const Bundle& bundle, std::span<const PairRows> pairs,
                                     std::span<NormalRow> normals, std::span<FrictionRow> frictions) const {
  {
    for (int lane = 0; lane < kLanes; ++lane) {
      if (bundle.pair[lane] < 0) continue;
      const PairRows& pair = pairs[static_cast<std::size_t>(bundle.pair[lane])];
      for (int i = 0; i < pair.pointCount; ++i) {
        const WidePoint& wide = m_points[static_cast<std::size_t>(bundle.firstPoint + i)];
        normals[static_cast<std::size_t>(pair.firstPoint + i)].impulse = wide.normalImpulse.v[lane];
        if (!pair.hasFriction) continue;
        for (int k = 0; k < 2; ++k) {
          frictions[static_cast<std::size_t>(pair.firstFriction + 2 * i + k)].impulse =
              wide.tangentImpulse[k].v[lane];
        }
      }
    }
  }
}

}  // namespace talus
