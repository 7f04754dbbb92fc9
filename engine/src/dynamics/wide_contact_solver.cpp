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

void WideContactSolver::Build(std::span<const PairRows> pairs, std::span<const NormalRow> normals,
                              std::span<const FrictionRow> frictions, std::span<const PointCold> cold,
                              std::span<const Eigen::Matrix4d> blocks, const SolverBodies& bodies,
                              const PhaseRunner& runner) {
  m_overflow.clear();
  m_colourStart.clear();

  std::vector<ColourInput>& inputs = m_inputs;
  inputs.clear();
  for (const PairRows& pair : pairs) {
    inputs.push_back({.bodyA = pair.bodyA,
                      .bodyB = pair.bodyB,
                      .movesA = bodies.Moves(pair.bodyA),
                      .movesB = bodies.Moves(pair.bodyB),
                      .eligible = pair.pointCount <= kMaxBundlePoints});
  }
  ColourPairs(inputs, bodies.Count(), m_colourOf, m_used);

  // Pairs grouped by colour, pair order within a colour (a counting sort).
  int counts[kColourCount + 1] = {};
  for (const int colour : m_colourOf) ++counts[colour];
  int starts[kColourCount + 2] = {};
  for (int c = 0; c <= kColourCount; ++c) starts[c + 1] = starts[c] + counts[c];
  m_order.resize(pairs.size());
  {
    int next[kColourCount + 1];
    for (int c = 0; c <= kColourCount; ++c) next[c] = starts[c];
    for (std::size_t p = 0; p < pairs.size(); ++p)
      m_order[static_cast<std::size_t>(next[m_colourOf[p]]++)] = static_cast<int>(p);
  }
  for (int i = starts[kOverflowColour]; i < starts[kOverflowColour + 1]; ++i) {
    m_overflow.push_back(m_order[static_cast<std::size_t>(i)]);
  }

  // The layout, serially: each bundle's first pair (into m_order), lanes
  // and first wide point (a running sum of the bundles' most points).
  m_layout.clear();
  m_colourStart.push_back(0);
  int points = 0;
  for (int c = 0; c < kColourCount; ++c) {
    if (counts[c] == 0) continue;
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
  // Capacity is kept; every bundle and point is overwritten whole below.
  m_bundles.resize(m_layout.size());
  m_points.resize(static_cast<std::size_t>(points));

  // Packing, each bundle into its own header and points (any thread).
  const JobPhase phase{.count = static_cast<int>(m_layout.size()), .grain = kPackBundleGrain};
  RunPhasesWith(runner, std::span<const JobPhase>(&phase, 1), [&](int, int begin, int end) {
    for (int b = begin; b < end; ++b) {
      const BundleLayout& layout = m_layout[static_cast<std::size_t>(b)];
      Bundle& bundle = m_bundles[static_cast<std::size_t>(b)];
      bundle = Bundle{};
      bundle.firstPoint = layout.firstPoint;
      bundle.points = layout.points;
      for (int i = 0; i < layout.points; ++i) m_points[static_cast<std::size_t>(layout.firstPoint + i)] = {};
      for (int lane = 0; lane < layout.lanes; ++lane) {
        const int p = m_order[static_cast<std::size_t>(layout.firstOrder + lane)];
        const PairRows& pair = pairs[static_cast<std::size_t>(p)];
        bundle.pair[lane] = p;
        bundle.bodyA[lane] = pair.bodyA;
        bundle.bodyB[lane] = pair.bodyB;
        if (bodies.Moves(pair.bodyA)) bundle.storeBitsA |= 1u << lane;
        if (bodies.Moves(pair.bodyB)) bundle.storeBitsB |= 1u << lane;
        if (pair.hasFriction) bundle.frictionBits |= 1u << lane;
        if (!pair.persisted) bundle.newBits |= 1u << lane;
        Put(bundle.normal, lane, pair.normal);
        Put(bundle.tangent[0], lane, pair.tangent[0]);
        Put(bundle.tangent[1], lane, pair.tangent[1]);
        bundle.invMassA.v[lane] = pair.invMassA;
        bundle.invMassB.v[lane] = pair.invMassB;
        bundle.friction.v[lane] = pair.friction;
        const Mat3& inertiaA = bodies.InvInertia(pair.bodyA);
        const Mat3& inertiaB = bodies.InvInertia(pair.bodyB);
        for (int i = 0; i < 3; ++i) {
          for (int j = 0; j < 3; ++j) {
            bundle.invInertiaA[3 * i + j].v[lane] = inertiaA(i, j);
            bundle.invInertiaB[3 * i + j].v[lane] = inertiaB(i, j);
          }
        }
        if (pair.block >= 0) {
          bundle.blockBits |= 1u << lane;
          const Eigen::Matrix4d& k = blocks[static_cast<std::size_t>(pair.block)];
          for (int i = 0; i < 4; ++i) {
            for (int j = 0; j < 4; ++j) bundle.block[4 * i + j].v[lane] = k(i, j);
          }
        }
        for (int i = 0; i < pair.pointCount; ++i) {
          const std::size_t point = static_cast<std::size_t>(pair.firstPoint + i);
          const NormalRow& row = normals[point];
          WidePoint& wide = m_points[static_cast<std::size_t>(bundle.firstPoint + i)];
          Put(wide.armA, lane, cold[point].armA);
          Put(wide.armB, lane, cold[point].armB);
          wide.normalMass.v[lane] = row.mass;
          wide.target.v[lane] = row.target;
          wide.normalImpulse.v[lane] = row.impulse;
          if (!pair.hasFriction) continue;
          for (int k = 0; k < 2; ++k) {
            const FrictionRow& f = frictions[static_cast<std::size_t>(pair.firstFriction + 2 * i + k)];
            wide.tangentMass[k].v[lane] = f.mass;
            wide.tangentImpulse[k].v[lane] = f.impulse;
          }
        }
      }
    }
  });
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
