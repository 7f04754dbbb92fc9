// Builds a box hull through the installed public API and checks it, then
// runs README's pair-query example (collide_two_boxes.h).
#include <cmath>
#include <cstdio>

#include <talus/hull.h>

#include "collide_two_boxes.h"

int main() {
  auto box = talus::Hull::Box({0.5, 1.0, 1.5});
  if (!box || box.Value().FaceCount() != 6 || box.Value().VertexCount() != 8) {
    std::fprintf(stderr, "consumer: box hull is wrong\n");
    return 1;
  }
  std::printf("consumer: box with %d faces\n", box.Value().FaceCount());
  // README's pair-query example, against the installed headers.
  const double depth = CollideTwoBoxes();
  if (!(std::abs(depth - 0.02) < 1e-12)) {
    std::fprintf(stderr, "consumer: pair query depth %g, expected 0.02\n", depth);
    return 1;
  }
  return 0;
}
