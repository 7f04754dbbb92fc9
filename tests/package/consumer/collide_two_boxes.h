// README's "Using the engine" example, kept here so that the consumer
// build and tests/collision/readme_example_test.cpp compile and run it, and
// the test checks README quotes this file verbatim.
#pragma once

#include <cstdio>

#include <talus/pair_query.h>

// Collides a 1 m cube with a 4 x 1 x 4 m slab it sinks 2 cm into; returns
// the depth (metres), or -1 on error.
inline double CollideTwoBoxes() {
  using namespace talus;
  const Shape cube = Shape::CreateBox({0.5, 0.5, 0.5}).Value();  // half extents, metres
  const Shape ground = Shape::CreateBox({2.0, 0.5, 2.0}).Value();
  const Transform onTop{.position = {0.0, 0.98, 0.0}};  // metres; identity rotation
  const Transform atOrigin{};
  const Result<PairContact> contact = CollideShapes(cube, onTop, ground, atOrigin);
  if (!contact) {
    std::fprintf(stderr, "%s\n", contact.GetError().message.c_str());
    return -1.0;
  }
  const PairContact& c = contact.Value();
  // c.normal points from B (ground) towards A (cube): (0, 1, 0).
  for (int i = 0; i < c.pointCount; ++i) {
    const PairContactPoint& p = c.points[static_cast<std::size_t>(i)];
    std::printf("point (%g, %g, %g) depth %g m\n", p.position.x(), p.position.y(), p.position.z(), p.depth);
  }
  return c.Depth();  // 0.02
}
