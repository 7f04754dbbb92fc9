// Builds a box hull through the installed public API and checks its volume.
#include <cmath>
#include <cstdio>

#include <talus/hull.h>

int main() {
  auto box = talus::Hull::Box({0.5, 1.0, 1.5});
  if (!box || box.Value().FaceCount() != 6 || box.Value().VertexCount() != 8) {
    std::fprintf(stderr, "consumer: box hull is wrong\n");
    return 1;
  }
  std::printf("consumer: box with %d faces\n", box.Value().FaceCount());
  return 0;
}
