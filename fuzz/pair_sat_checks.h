// The pair query's invariants against a brute-force separating axis test
// written here (no engine collision code shared), for the pair_sat fuzz
// target and the corpus replay in tests/fuzz/.
//
// Input bytes: byte 0 picks the SAT mode (bit 0: Full or GaussMapPruned)
// and whether each shape is a box (bits 1, 2) instead of a hull; byte 1
// gives A's point count (4 + b % 9), byte 2 B's; then little-endian
// doubles read as fractions (fmod 1, non-finite as 0): A's points, B's
// points (or three half extents for a box), then each pose as a position
// (3 values scaled to +-2 m) and a quaternion (4 values, normalised;
// identity when near zero). Missing values are 0.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "talus/math.h"
#include "talus/narrow_phase.h"
#include "talus/transform.h"

namespace talus::fuzz {

/// One shape of a fuzzed pair: hull points or a box's half extents.
struct FuzzShape {
  bool box = false;
  std::vector<Vec3> points;  ///< hull input (box: empty)
  Vec3 halfExtents = Vec3::Ones();
  Transform pose;
};

struct PairInput {
  SatMode satMode = SatMode::GaussMapPruned;
  FuzzShape a, b;
};

PairInput DecodePairInput(std::span<const std::uint8_t> data);

/// Runs CollideShapes on the pair (margin 0) and checks it against a
/// brute-force SAT over every face normal of both shapes and the cross
/// product of every edge pair, each axis with its own round-off bound:
/// - an axis that separates by more than its bound means "not touching";
/// - every axis overlapping by more than its bound means "touching";
/// - touching: the depth is the least overlap over all axes, to
///   kAxisPreferenceRelative x the pair's size plus round-off;
/// - not touching: the reported normal separates the shapes by the
///   reported gap (both measured here by projecting the vertices).
/// A pair whose hull the builder refuses is skipped. Empty when every
/// check passes, else what failed.
std::string CheckPairSat(const PairInput& input);

}  // namespace talus::fuzz
