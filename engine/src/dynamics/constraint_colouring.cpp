// Greedy first-fit colouring of the contact pairs (see the header).
#include "dynamics/constraint_colouring.h"

#include <bit>
#include <cassert>

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
}

}  // namespace talus
