// UniformGrid: the write-up's broad phase, a uniform grid of cubic cells
// binning the bodies' bounding spheres, hashed so that memory follows the
// occupied cells and not the extent of the world.
//
// Owns, rebuilt every step from the proxies (bodies move every step, so a
// rebuild costs no more than moving entries between cells and is simpler):
// - the cell edge h = kCellSizeFactor x the largest dynamic diameter
//   (>= kMinCellSize), so every dynamic body overlaps at most 2x2x2 cells;
// - an open-addressing hash table (linear probing, power-of-two size, at
//   most half full) from integer cell coordinates to a dense cell array;
// - the proxies of each cell, contiguous and in increasing slot order
//   (a counting sort by cell);
// - the oversized list: bodies wider than kOversizedCellSpan cells (huge
//   static floors and walls), sphere-tested against every body instead of
//   being binned into thousands of cells.
// Each pair sharing cells is reported once, in its lowest shared cell (the
// cell holding the minimum corner of the two boxes' overlap), so no set or
// sort is needed to deduplicate. All buffers keep their capacity, so a
// steady-state step allocates nothing. Output order is sorted (a, b) and
// depends only on the proxies, never on hash table layout.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "collision/broad_phase_proxy.h"
#include "talus/broad_phase.h"

namespace talus {

class UniformGrid {
 public:
  /// Appends to `out` (cleared first) every pair of active proxies, not both
  /// static, whose spheres touch, sorted by (a, b). Fills candidatePairs,
  /// spherePairs, skippedStaticPairs, oversizedProxies, oversizedTests,
  /// cellSize and occupiedCells of `stats`.
  void FindPairs(std::span<const BroadPhaseProxy> proxies, std::vector<BroadPhasePair>& out,
                 BroadPhaseStats& stats);

  /// The cell edge (m) a set of proxies gets: kCellSizeFactor x the largest
  /// active dynamic bounding-sphere diameter, at least kMinCellSize; 0 when
  /// there is no active dynamic proxy (then no pair can exist).
  static double CellSizeFor(std::span<const BroadPhaseProxy> proxies);

 private:
  struct CellCoord {
    std::int64_t x = 0;
    std::int64_t y = 0;
    std::int64_t z = 0;
    friend bool operator==(const CellCoord&, const CellCoord&) = default;
  };
  struct Cell {
    CellCoord coord;
    int count = 0;  ///< proxies in the cell
    int start = 0;  ///< first of them in m_members
  };
  struct Entry {
    int cell = 0;
    int proxy = 0;
  };

  /// Bins every active proxy that is not oversized; fills m_entries, m_cells.
  void BinProxies(std::span<const BroadPhaseProxy> proxies, double inverseCellSize, double cellSize);
  /// Index of the cell at `c` in m_cells, adding it if new.
  int FindOrAddCell(const CellCoord& c);
  /// Clears the hash table to `size` empty slots (a power of two).
  void ResetTable(std::size_t size);
  /// Pairs among the members of each cell, reported in their lowest shared cell.
  void PairsInCells(std::span<const BroadPhaseProxy> proxies, std::vector<BroadPhasePair>& out,
                    BroadPhaseStats& stats);
  /// Pairs of each oversized proxy with every other active proxy.
  void PairsWithOversized(std::span<const BroadPhaseProxy> proxies, std::vector<BroadPhasePair>& out,
                          BroadPhaseStats& stats);

  std::vector<int> m_table;          ///< hash slot -> index into m_cells, -1 empty
  std::vector<Cell> m_cells;         ///< occupied cells this step
  std::vector<Entry> m_entries;      ///< (cell, proxy) per binned overlap, by proxy
  std::vector<int> m_members;        ///< proxies grouped by cell (counting sort)
  std::vector<CellCoord> m_lowCell;  ///< per slot: cell of the box's min corner
  std::vector<int> m_oversized;      ///< oversized active slots, increasing
  std::vector<char> m_isOversized;   ///< per slot flag
};

}  // namespace talus
