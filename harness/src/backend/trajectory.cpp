// Which steps a run records, and which of its samples a plot or a replay
// keeps (see talus/harness/backend/trajectory.h).
#include "talus/harness/backend/trajectory.h"

#include <algorithm>
#include <cassert>

namespace talus::harness {

int SampleStride(int steps, int maxSamples) {
  assert(maxSamples >= 1);
  if (steps <= maxSamples) return 1;
  return 1 + (steps - 1) / maxSamples;  // ceil(steps / maxSamples) without steps + maxSamples overflowing
}

bool IsSampled(int step, int steps, int stride) { return step % stride == 0 || step == steps; }

std::vector<std::size_t> SpreadIndices(std::size_t count, std::size_t most) {
  std::vector<std::size_t> indices;
  const std::size_t points = std::min(count, most);
  for (std::size_t i = 0; i < points; ++i) {
    const std::size_t index = points == 1 ? 0 : i * (count - 1) / (points - 1);
    if (!indices.empty() && indices.back() == index) continue;
    indices.push_back(index);
  }
  return indices;
}

}  // namespace talus::harness
