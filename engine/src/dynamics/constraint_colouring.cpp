// Greedy first-fit colouring of the contact pairs (see the header).
#include "dynamics/constraint_colouring.h"

#include <bit>
#include <cassert>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace talus {

static_assert(kColourCount <= 32, "one bit per colour in a 32-bit mask");

void ColourPairs(std::span<const ColourInput> pairs, int bodyCount, std::vector<int>& colours,
                 std::vector<std::uint32_t>& usedScratch) {
  usedScratch.assign(static_cast<std::size_t>(bodyCount), 0u);
  colours.resize(pairs.size());
  constexpr std::uint32_t kAll = kColourCount == 32 ? ~0u : ((1u << kColourCount) - 1u);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const ColourInput& pair = pairs[i];
    assert(pair.bodyA >= 0 && pair.bodyA < bodyCount && pair.bodyB >= 0 && pair.bodyB < bodyCount);
    std::uint32_t taken = 0;
    if (pair.movesA) taken |= usedScratch[static_cast<std::size_t>(pair.bodyA)];
    if (pair.movesB) taken |= usedScratch[static_cast<std::size_t>(pair.bodyB)];
    const std::uint32_t free = ~taken & kAll;
    if (!pair.eligible || free == 0) {
      colours[i] = kOverflowColour;
      continue;
    }
    const int colour = std::countr_zero(free);
    colours[i] = colour;
    const std::uint32_t bit = 1u << colour;
    if (pair.movesA) usedScratch[static_cast<std::size_t>(pair.bodyA)] |= bit;
    if (pair.movesB) usedScratch[static_cast<std::size_t>(pair.bodyB)] |= bit;
  }
#if defined(TALUS_VALIDATE)
  if (const std::string failure = CheckColouring(pairs, bodyCount, colours); !failure.empty()) {
    std::fprintf(stderr, "talus validation failed: %s\n", failure.c_str());
    std::abort();
  }
#endif
}

std::string CheckColouring(std::span<const ColourInput> pairs, int bodyCount, std::span<const int> colours) {
  if (colours.size() != pairs.size()) {
    return std::string("colours: ") + std::to_string(colours.size()) + " colours for " +
           std::to_string(pairs.size()) + " pairs";
  }
  // owner[body * kColourCount + colour]: the pair of that colour that moves the body, or -1.
  std::vector<int> owner(static_cast<std::size_t>(bodyCount) * kColourCount, -1);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const int colour = colours[i];
    if (colour < 0 || colour > kOverflowColour) {
      return std::string("colours: pair ") + std::to_string(i) + " has colour " + std::to_string(colour) +
             " (0 to " + std::to_string(kOverflowColour) + ")";
    }
    if (colour == kOverflowColour) continue;
    for (const auto& [body, moves] :
         {std::pair{pairs[i].bodyA, pairs[i].movesA}, std::pair{pairs[i].bodyB, pairs[i].movesB}}) {
      if (!moves) continue;
      if (body < 0 || body >= bodyCount) {
        return std::string("colours: pair ") + std::to_string(i) + " names body " + std::to_string(body) +
               std::string(" outside [0, ") + std::to_string(bodyCount) + ")";
      }
      int& first = owner[static_cast<std::size_t>(body) * kColourCount + static_cast<std::size_t>(colour)];
      if (first >= 0) {
        return std::string("colours: pairs ") + std::to_string(first) + " and " + std::to_string(i) +
               " of colour " + std::to_string(colour) + " both move body " + std::to_string(body);
      }
      first = static_cast<int>(i);
    }
  }
  return {};
}

}  // namespace talus
