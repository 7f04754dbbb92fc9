// Uses an installed Talus the way an application would: one include, a box
// hull, README's pair-query example (collide_two_boxes.h), then a 1 m cube
// dropped on a static ground box and stepped to rest.
#include <cmath>
#include <cstdio>

#include <talus/talus.h>

#include "collide_two_boxes.h"

namespace {

int Fail(const char* what) {
  std::fprintf(stderr, "consumer: %s\n", what);
  return 1;
}

}  // namespace

int main() {
  auto box = talus::Hull::Box({0.5, 1.0, 1.5});
  if (!box || box.Value().FaceCount() != 6 || box.Value().VertexCount() != 8)
    return Fail("box hull is wrong");

  // README's example: the cube sinks 2 cm into the slab.
  const double depth = CollideTwoBoxes();
  if (!(std::abs(depth - 0.02) < 1e-12)) return Fail("pair query depth is not the 2 cm overlap");

  auto world = talus::World::Create(talus::WorldSettings{});
  auto ground = talus::Shape::CreateBox({10.0, 0.5, 10.0});
  auto cube = talus::Shape::CreateBox({0.5, 0.5, 0.5});
  if (!world || !ground || !cube) return Fail("world or shapes refused");
  talus::World& w = world.Value();
  if (!w.CreateBody({.position = {0.0, -0.5, 0.0}, .shape = ground.Value()})) return Fail("ground refused");
  auto body = w.CreateBody({.type = talus::BodyType::Dynamic,
                            .position = {0.0, 0.6, 0.0},
                            .shape = cube.Value(),
                            .density = 1000.0});
  if (!body) return Fail("cube refused");
  for (int step = 0; step < 120; ++step) {
    if (!w.Step(1.0 / 60.0)) return Fail("step refused");
  }
  const auto state = w.GetBodyState(body.Value());
  if (!state) return Fail("state refused");
  // At rest its centre is 0.5 m up (a resting box settles within 3e-7 m of
  // it, MethodSettings::narrowPhase.speculativeMargin): 1 mm covers it with
  // margin while a cube that fell through or bounced off is metres away.
  const double height = state.Value().position.y();
  if (std::abs(height - 0.5) > 1e-3) return Fail("cube did not come to rest on the ground");
  std::printf("consumer: box with %d faces; cube at rest at y = %.6f m\n", box.Value().FaceCount(), height);
  return 0;
}
