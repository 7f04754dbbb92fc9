// Uniform grid broad phase (write-up section 2): bounding spheres binned in a
// hashed grid of cubic cells sized by the largest dynamic body, candidate
// pairs from shared cells, the sphere-sphere test, and an oversized list for
// the few huge static bodies (floors, walls) a grid sized for the dynamic
// bodies cannot hold. The deduplication by lowest shared cell is the usual
// trick for multi-cell binning (e.g. Ericson, Real-Time Collision Detection,
// 7.1.7): a pair is reported only by the cell containing the minimum corner
// of the intersection of the two bodies' cell ranges.
#include "collision/uniform_grid.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace talus {
namespace {

// Mixes three cell coordinates into a 64-bit hash (multiply by odd
// constants, then the SplitMix64 finaliser), so neighbouring cells spread
// over the table.
std::uint64_t HashCell(std::int64_t x, std::int64_t y, std::int64_t z) {
  std::uint64_t h = static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull;
  h ^= static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4Full;
  h ^= static_cast<std::uint64_t>(z) * 0x165667B19E3779F9ull;
  h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
  h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
  return h ^ (h >> 31);
}

std::int64_t CellIndex(double coordinate, double inverseCellSize) {
  return static_cast<std::int64_t>(std::floor(coordinate * inverseCellSize));
}

constexpr std::size_t kInitialTableSize = 64;

}  // namespace

double UniformGrid::CellSizeFor(std::span<const BroadPhaseProxy> proxies) {
  double largestDiameter = -1.0;
  for (const BroadPhaseProxy& p : proxies) {
    if (p.active && !p.isStatic) largestDiameter = std::max(largestDiameter, 2.0 * p.sphere.radius);
  }
  if (largestDiameter < 0.0) return 0.0;
  return std::max(kCellSizeFactor * largestDiameter, kMinCellSize);
}

void UniformGrid::FindPairs(std::span<const BroadPhaseProxy> proxies, std::vector<BroadPhasePair>& out,
                            BroadPhaseStats& stats) {
  out.clear();
  m_cells.clear();
  m_entries.clear();
  m_oversized.clear();
  stats.candidatePairs = 0;
  stats.skippedStaticPairs = 0;
  stats.oversizedTests = 0;
  const double cellSize = CellSizeFor(proxies);
  stats.cellSize = cellSize;
  // Without a dynamic body every pair is static-static: nothing to bin.
  if (cellSize == 0.0) {
    stats.spherePairs = 0;
    stats.oversizedProxies = 0;
    stats.occupiedCells = 0;
    return;
  }

  BinProxies(proxies, 1.0 / cellSize, cellSize);
  PairsInCells(proxies, out, stats);
  PairsWithOversized(proxies, out, stats);
  std::sort(out.begin(), out.end());

  stats.spherePairs = static_cast<std::int64_t>(out.size());
  stats.oversizedProxies = static_cast<int>(m_oversized.size());
  stats.occupiedCells = static_cast<int>(m_cells.size());
}

void UniformGrid::BinProxies(std::span<const BroadPhaseProxy> proxies, double inverseCellSize,
                             double cellSize) {
  ResetTable(std::max(m_table.size(), kInitialTableSize));
  m_lowCell.resize(proxies.size());
  m_isOversized.assign(proxies.size(), 0);
  const double oversizedDiameter = kOversizedCellSpan * cellSize;

  for (std::size_t i = 0; i < proxies.size(); ++i) {
    const BroadPhaseProxy& p = proxies[i];
    if (!p.active) continue;
    if (2.0 * p.sphere.radius > oversizedDiameter) {
      m_oversized.push_back(static_cast<int>(i));
      m_isOversized[i] = 1;
      continue;
    }
    const Aabb box = ProxyBox(p.sphere);
    const CellCoord lo{CellIndex(box.min.x(), inverseCellSize), CellIndex(box.min.y(), inverseCellSize),
                       CellIndex(box.min.z(), inverseCellSize)};
    const CellCoord hi{CellIndex(box.max.x(), inverseCellSize), CellIndex(box.max.y(), inverseCellSize),
                       CellIndex(box.max.z(), inverseCellSize)};
    m_lowCell[i] = lo;
    for (std::int64_t z = lo.z; z <= hi.z; ++z) {
      for (std::int64_t y = lo.y; y <= hi.y; ++y) {
        for (std::int64_t x = lo.x; x <= hi.x; ++x) {
          const int cell = FindOrAddCell({x, y, z});
          ++m_cells[static_cast<std::size_t>(cell)].count;
          m_entries.push_back({cell, static_cast<int>(i)});
        }
      }
    }
  }

  // Counting sort of the entries by cell; entries arrive by increasing slot,
  // so each cell's members come out increasing too.
  int start = 0;
  for (Cell& cell : m_cells) {
    cell.start = start;
    start += cell.count;
    cell.count = 0;
  }
  m_members.resize(m_entries.size());
  for (const Entry& e : m_entries) {
    Cell& cell = m_cells[static_cast<std::size_t>(e.cell)];
    m_members[static_cast<std::size_t>(cell.start + cell.count)] = e.proxy;
    ++cell.count;
  }
}

void UniformGrid::ResetTable(std::size_t size) {
  assert((size & (size - 1)) == 0);
  m_table.assign(size, -1);
}

int UniformGrid::FindOrAddCell(const CellCoord& c) {
  // Keep the table at most half full so probe runs stay short.
  if (2 * (m_cells.size() + 1) > m_table.size()) {
    ResetTable(2 * m_table.size());
    const std::size_t mask = m_table.size() - 1;
    for (std::size_t k = 0; k < m_cells.size(); ++k) {
      const CellCoord& old = m_cells[k].coord;
      std::size_t slot = HashCell(old.x, old.y, old.z) & mask;
      while (m_table[slot] >= 0) slot = (slot + 1) & mask;
      m_table[slot] = static_cast<int>(k);
    }
  }
  const std::size_t mask = m_table.size() - 1;
  std::size_t slot = HashCell(c.x, c.y, c.z) & mask;
  while (true) {
    const int index = m_table[slot];
    if (index < 0) break;
    if (m_cells[static_cast<std::size_t>(index)].coord == c) return index;
    slot = (slot + 1) & mask;
  }
  const int index = static_cast<int>(m_cells.size());
  m_cells.push_back({c, 0, 0});
  m_table[slot] = index;
  return index;
}

void UniformGrid::PairsInCells(std::span<const BroadPhaseProxy> proxies, std::vector<BroadPhasePair>& out,
                               BroadPhaseStats& stats) {
  std::int64_t candidates = 0;
  std::int64_t skipped = 0;
  for (const Cell& cell : m_cells) {
    const int* members = m_members.data() + cell.start;
    for (int i = 0; i < cell.count; ++i) {
      const int a = members[i];
      const BroadPhaseProxy& pa = proxies[static_cast<std::size_t>(a)];
      const CellCoord& lowA = m_lowCell[static_cast<std::size_t>(a)];
      for (int j = i + 1; j < cell.count; ++j) {
        const int b = members[j];
        const CellCoord& lowB = m_lowCell[static_cast<std::size_t>(b)];
        // Report the pair only in the lowest cell the two share.
        const CellCoord lowest{std::max(lowA.x, lowB.x), std::max(lowA.y, lowB.y), std::max(lowA.z, lowB.z)};
        if (!(lowest == cell.coord)) continue;
        const BroadPhaseProxy& pb = proxies[static_cast<std::size_t>(b)];
        if (pa.isStatic && pb.isStatic) {
          ++skipped;
          continue;
        }
        ++candidates;
        if (SpheresTouch(pa.sphere, pb.sphere)) out.push_back({a, b});
      }
    }
  }
  stats.candidatePairs += candidates;
  stats.skippedStaticPairs += skipped;
}

void UniformGrid::PairsWithOversized(std::span<const BroadPhaseProxy> proxies,
                                     std::vector<BroadPhasePair>& out, BroadPhaseStats& stats) {
  std::int64_t tests = 0;
  std::int64_t skipped = 0;
  for (const int o : m_oversized) {
    const BroadPhaseProxy& po = proxies[static_cast<std::size_t>(o)];
    for (std::size_t k = 0; k < proxies.size(); ++k) {
      const int p = static_cast<int>(k);
      const BroadPhaseProxy& pp = proxies[k];
      // Two oversized bodies are paired once, from the lower slot.
      if (!pp.active || p == o || (m_isOversized[k] && p < o)) continue;
      if (po.isStatic && pp.isStatic) {
        ++skipped;
        continue;
      }
      ++tests;
      if (SpheresTouch(po.sphere, pp.sphere)) out.push_back({std::min(o, p), std::max(o, p)});
    }
  }
  stats.candidatePairs += tests;
  stats.oversizedTests = tests;
  stats.skippedStaticPairs += skipped;
}

}  // namespace talus
