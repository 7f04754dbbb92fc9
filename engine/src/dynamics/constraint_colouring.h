// Graph colouring of the contact pairs: pairs of one colour share no body
// that contacts can move, so their rows can be solved in any order, several
// at once (SIMD lanes) or on several threads, with the same result (Box2D
// v3's constraint graph).
//
// Greedy first fit in the pairs' order: each pair takes the lowest colour
// that neither of its movable bodies has yet; immovable bodies (static,
// kinematic, asleep: zero inverse mass, never written by a row) do not
// count, so a floor under a thousand boxes does not force a thousand
// colours. A pair that finds no free colour among kColourCount, or that the
// caller marks ineligible, goes to the overflow colour, which the solver
// runs one pair at a time after the colours. The result is a function of
// the input order alone (deterministic).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace talus {

/// Colours before overflow. 24 as Box2D v3 (b2_graphColorCount): a cube in
/// a 3D pyramid touches at most 12 others, so greedy first fit needs at
/// most 13; hull piles measured below 20.
inline constexpr int kColourCount = 24;
/// The colour of a pair that found no free colour (or was not eligible).
inline constexpr int kOverflowColour = kColourCount;

/// One pair to colour: its two solver-body indices and whether each can be
/// moved by contacts.
struct ColourInput {
  int bodyA = -1;
  int bodyB = -1;
  bool movesA = false;
  bool movesB = false;
  bool eligible = true;  ///< false: straight to the overflow colour
};

/// Colours `pairs` in order into `colours` (resized, one per pair, in [0,
/// kColourCount] with kOverflowColour for overflow). `bodyCount` bounds
/// every body index. `usedScratch` is working memory kept by the caller so
/// that nothing allocates in steady state.
void ColourPairs(std::span<const ColourInput> pairs, int bodyCount, std::vector<int>& colours,
                 std::vector<std::uint32_t>& usedScratch);

/// The colouring's invariant, for the validation pass (world/world_validate.h):
/// one colour per pair, each in [0, kOverflowColour], and no two pairs of
/// one colour (the overflow aside) share a body that contacts move. Empty
/// when it holds, else a message naming the colour, the body and the two
/// pairs. Built with TALUS_VALIDATE, ColourPairs checks its own result and
/// aborts on a failure.
std::string CheckColouring(std::span<const ColourInput> pairs, int bodyCount, std::span<const int> colours);

}  // namespace talus
