// ColouredContactDispatch: the coloured passes as chains of phases on the
// solver's threads (see dynamics/coloured_contact_dispatch.h).
#include "dynamics/coloured_contact_dispatch.h"

#include <atomic>
#include <cstdint>

namespace talus {

namespace {

// Bundles per chunk of the coloured warm start (a bundle is well under a
// microsecond of work).
constexpr int kWarmStartBundleGrain = 16;
// Bundles (four pairs each) per chunk of a colour's pass: a bundle's rows
// are about a microsecond, so a chunk is well above the cost of claiming
// it, and the smaller colours still split across two threads.
constexpr int kSweepBundleGrain = 8;

}  // namespace

void ColouredContactDispatch::Build(const ContactRowSet& rows, const PhaseRunner& runner,
                                    StepStatistics& stats) {
  m_wide.Build(rows.Pairs(), rows.Normals(), rows.Frictions(), rows.Cold(), rows.BlockInverses(),
               rows.Bodies(), runner);
  stats.solverColours = m_wide.ColourCount();
  stats.overflowPairs = static_cast<std::int64_t>(m_wide.OverflowPairs().size());
}

// One chain of phases: each colour, then the overflow pairs as one chunk.
void ColouredContactDispatch::WarmStart(ContactRowSet& rows, const PhaseRunner& runner) {
  const int colours = m_wide.ColourCount();
  m_phases.clear();
  for (int colour = 0; colour < colours; ++colour) {
    m_phases.push_back({.count = m_wide.BundleCount(colour), .grain = kWarmStartBundleGrain});
  }
  m_phases.push_back({.count = m_wide.OverflowPairs().empty() ? 0 : 1, .grain = 1});
  RunPhasesWith(runner, m_phases, [this, &rows, colours](int phase, int begin, int end) {
    if (phase < colours) {
      m_wide.WarmStartRange(rows.Bodies(), phase, begin, end);
      return;
    }
    for (const int p : m_wide.OverflowPairs()) {
      SequentialImpulseSweeps::WarmStartPair(rows, rows.Pairs()[static_cast<std::size_t>(p)]);
    }
  });
}

// Each sweep is 2 (colours + 1) phases: the colours' normal rows, the
// overflow pairs' normal rows (one chunk: they run one by one, in order),
// then the same for the friction rows. A colour's bundles are split into
// chunks of kSweepBundleGrain; the phases of all `sweeps` sweeps are one
// chain, so the threads meet once per phase on finished chunks instead of
// being handed a new job per colour.
double ColouredContactDispatch::Sweeps(ContactRowSet& rows, CoupledBlockSolver& coupled,
                                       SequentialImpulseSweeps& overflow, int sweeps, bool track,
                                       const PhaseRunner& runner) {
  const int colours = m_wide.ColourCount();
  const int perSweep = 2 * (colours + 1);
  const int overflowChunks = m_wide.OverflowPairs().empty() ? 0 : 1;
  m_phases.clear();
  for (int s = 0; s < sweeps; ++s) {
    for (int pass = 0; pass < 2; ++pass) {
      for (int colour = 0; colour < colours; ++colour) {
        m_phases.push_back({.count = m_wide.BundleCount(colour), .grain = kSweepBundleGrain});
      }
      m_phases.push_back({.count = overflowChunks, .grain = 1});
    }
  }
  std::atomic<double> largest{0.0};
  RunPhasesWith(runner, m_phases, [&](int phase, int begin, int end) {
    const int inSweep = phase % perSweep;
    const bool friction = inSweep > colours;
    const int colour = friction ? inSweep - colours - 1 : inSweep;
    double mine = 0.0;
    if (colour < colours) {
      mine = friction ? m_wide.SolveFrictionRange(rows.Bodies(), colour, begin, end, track)
                      : m_wide.SolveNormalRange(rows.Bodies(), colour, begin, end, track);
    } else {
      // The overflow pairs one by one with the scalar passes (the phases
      // before and after this one's single chunk order every other access
      // to `overflow`).
      mine = overflow.SolvePairs(rows, coupled, m_wide.OverflowPairs(), friction, track);
    }
    double seen = largest.load(std::memory_order_relaxed);
    while (mine > seen && !largest.compare_exchange_weak(seen, mine, std::memory_order_relaxed)) {
    }
  });
  return largest.load(std::memory_order_relaxed);
}

void ColouredContactDispatch::Unpack(ContactRowSet& rows, const PhaseRunner& runner) const {
  m_wide.Unpack(rows.Pairs(), rows.Normals(), rows.Frictions(), runner);
}

}  // namespace talus
