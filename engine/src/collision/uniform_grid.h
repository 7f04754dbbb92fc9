// UniformGrid: the write-up's broad phase, a uniform grid of cubic cells
// binning the bodies' bounding spheres, stored sparsely so that memory
// follows the occupied cells and not the extent of the world.
//
// Owns, rebuilt every step from the proxies (bodies move every step, so a
// rebuild costs no more than moving entries between cells and is simpler):
// - the cell edge h = kCellSizeFactor x the largest dynamic diameter
//   (>= kMinCellSize), so every dynamic body overlaps at most 2x2x2 cells;
// - one entry (cell key, slot) per cell a body overlaps. The key packs the
//   cell's integer coordinates relative to the lowest occupied cell, with
//   just enough bits per axis for the occupied range; a stable LSD radix
//   sort on the key groups each cell's bodies together, in increasing slot
//   order. This is a "sorted cell list" (the layout GPU broad phases use,
//   e.g. Le Grand, GPU Gems 3 ch. 32) in place of a hash table: a hash table
//   of 10^5 cells missed the cache on nearly every lookup (measured 7x
//   slower at 100k bodies, see docs/collision-broad-phase.md), while the
//   radix passes stream through memory. Memory is O(entries) <= 8 per
//   dynamic body (kOversizedCellSpan bounds the rest), whatever the world's size;
// - the oversized list: bodies wider than kOversizedCellSpan cells (huge
//   static floors and walls), sphere-tested against every body instead of
//   being binned into thousands of cells.
// Each pair sharing cells is reported once, in its lowest shared cell (the
// cell holding the minimum corner of the two bodies' cell ranges), so no set
// is needed to deduplicate. If the occupied range needs more than 64 key
// bits (2^21 cells per axis, thousands of km with metre bodies) the grid
// declines the step and the caller uses another structure. All buffers keep
// their capacity, so a steady-state step allocates nothing. Output order is
// sorted (a, b) and depends only on the proxies.
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
  /// cellSize and occupiedCells of `stats`. Returns false, with `out` empty,
  /// when the occupied cells span more than a 64-bit key can address.
  bool FindPairs(std::span<const BroadPhaseProxy> proxies, std::vector<BroadPhasePair>& out,
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
  };
  struct Entry {
    std::uint64_t key = 0;  ///< packed cell coordinates
    int proxy = 0;
  };
  // Radix-sorted every step, twice per pass (docs/collision-broad-phase.md,
  // Record sizes).
  static_assert(sizeof(Entry) == 16, "UniformGrid::Entry: cell key and proxy (padded to 8)");
  /// What the pair loop reads of a cell's member, gathered once per entry
  /// so the loop streams through memory instead of jumping between slots.
  struct Member {
    Sphere sphere;
    std::uint64_t lowX = 0;  ///< lowest cell of the body's range, relative
    std::uint64_t lowY = 0;  ///< to m_origin
    std::uint64_t lowZ = 0;
    int proxy = 0;
    bool isStatic = false;
  };
  // One cache line each: the pair loop streams members cell by cell
  // (docs/collision-broad-phase.md, Record sizes).
  static_assert(sizeof(Member) == 64, "UniformGrid::Member: one cache line");

  /// Finds each active proxy's cell range and the oversized ones; returns
  /// false when the occupied range needs more than 64 key bits.
  bool RangeProxies(std::span<const BroadPhaseProxy> proxies, double inverseCellSize, double cellSize);
  /// The packed key of a cell inside the occupied range.
  [[nodiscard]] std::uint64_t Key(std::int64_t x, std::int64_t y, std::int64_t z) const {
    return static_cast<std::uint64_t>(x - m_origin.x) |
           static_cast<std::uint64_t>(y - m_origin.y) << m_shiftY |
           static_cast<std::uint64_t>(z - m_origin.z) << m_shiftZ;
  }
  /// One entry per (cell, binned proxy), sorted by key, slots increasing.
  void BinAndSort();
  /// Pairs among the members of each cell, reported in their lowest shared cell.
  void PairsInCells(std::span<const BroadPhaseProxy> proxies, std::vector<BroadPhasePair>& out,
                    BroadPhaseStats& stats);
  /// Pairs of each oversized proxy with every other active proxy.
  void PairsWithOversized(std::span<const BroadPhaseProxy> proxies, std::vector<BroadPhasePair>& out,
                          BroadPhaseStats& stats);

  CellCoord m_origin;                 ///< lowest occupied cell this step
  int m_shiftY = 0;                   ///< key bit where y starts
  int m_shiftZ = 0;                   ///< key bit where z starts
  int m_keyBits = 0;                  ///< bits used by keys this step
  std::vector<Entry> m_entries;       ///< (cell, proxy), sorted by key
  std::vector<Entry> m_scratch;       ///< radix sort ping-pong buffer
  std::vector<Member> m_members;      ///< m_entries' bodies, same order
  std::vector<CellCoord> m_lowCell;   ///< per slot: lowest cell of its range
  std::vector<CellCoord> m_highCell;  ///< per slot: highest cell of its range
  std::vector<int> m_binned;          ///< binned active slots, increasing
  std::vector<int> m_oversized;       ///< oversized active slots, increasing
  std::vector<char> m_isOversized;    ///< per slot flag
  int m_occupiedCells = 0;
};

}  // namespace talus
