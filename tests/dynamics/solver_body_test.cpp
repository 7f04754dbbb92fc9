// The solver's own body array and precomputed rows: gather/scatter touches
// only the bodies contacts can move, and a row solved through its
// precomputed Jacobian gives the analytic impulse of a resting box.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "contact_scene.h"
#include "dynamics/solver_body.h"

namespace talus {
namespace solver_body_test {

using testing::ContactScene;

constexpr double kH = 1.0 / 60.0;
constexpr double kG = 9.81;

bool SameBits(const Vec3& a, const Vec3& b) {
  return std::memcmp(a.data(), b.data(), 3 * sizeof(double)) == 0;
}

BodySim Dynamic(const Vec3& v, const Vec3& w) {
  BodySim body;
  body.type = BodyType::Dynamic;
  body.invMass = 0.5;
  body.invInertiaLocal = Mat3::Identity() * 3.0;
  body.UpdateWorldInertia();
  body.linearVelocity = v;
  body.angularVelocity = w;
  return body;
}

TEST(SolverBodies, AddGathersEachBodyOnceWithTheMassContactsSee) {
  std::vector<BodySim> bodies(4);
  bodies[1] = Dynamic({1, 2, 3}, {4, 5, 6});
  bodies[2] = Dynamic({0, -1, 0}, {0, 0, 0});
  bodies[2].awake = false;  // asleep: contacts cannot move it
  bodies[3].type = BodyType::Kinematic;
  bodies[3].linearVelocity = Vec3(0, 0, 7);
  SolverBodies solver;
  solver.Reset(bodies.size());
  EXPECT_EQ(solver.Add(bodies, 1), 0);
  EXPECT_EQ(solver.Add(bodies, 3), 1);
  EXPECT_EQ(solver.Add(bodies, 1), 0);  // same body, same entry
  EXPECT_EQ(solver.Add(bodies, 2), 2);
  EXPECT_EQ(solver.Count(), 3);
  EXPECT_EQ(solver.BodyIndex(1), 3);
  EXPECT_TRUE(SameBits(solver.Velocity(0).v, bodies[1].linearVelocity));
  EXPECT_TRUE(SameBits(solver.Velocity(0).w, bodies[1].angularVelocity));
  EXPECT_EQ(solver.InvMass(0), 0.5);
  EXPECT_EQ(solver.InvInertia(0), bodies[1].invInertiaWorld);
  // The kinematic body keeps its real velocity (rows read it) but no mass.
  EXPECT_TRUE(SameBits(solver.Velocity(1).v, bodies[3].linearVelocity));
  for (const int immovable : {1, 2}) {
    EXPECT_FALSE(solver.Moves(immovable));
    EXPECT_EQ(solver.InvMass(immovable), 0.0);
    EXPECT_EQ(solver.InvInertia(immovable), Mat3::Zero());
  }
  // A reset forgets the entries: the next step numbers bodies afresh.
  solver.Reset(bodies.size());
  EXPECT_EQ(solver.Count(), 0);
  EXPECT_EQ(solver.Add(bodies, 2), 0);
}

TEST(SolverBodies, ScatterWritesBackOnlyTheBodiesContactsMove) {
  std::vector<BodySim> bodies(4);
  bodies[0] = Dynamic({1, 2, 3}, {4, 5, 6});                // gathered, moved by the solver
  bodies[1] = Dynamic({-0.0, 0.25, 1e-300}, {-0.0, 0, 0});  // never gathered
  bodies[2].type = BodyType::Kinematic;                     // gathered, immovable
  bodies[2].linearVelocity = Vec3(-0.0, 1, 0);
  const std::vector<BodySim> before = bodies;
  SolverBodies solver;
  solver.Reset(bodies.size());
  const int moved = solver.Add(bodies, 0);
  const int kinematic = solver.Add(bodies, 2);
  solver.Velocity(moved).v = Vec3(9, 9, 9);
  solver.Pseudo(moved).w = Vec3(0, 1, 0);
  // Even a solver that wrote to an immovable entry leaves its body alone.
  solver.Velocity(kinematic).v = Vec3(5, 5, 5);
  solver.Scatter(bodies, true);
  EXPECT_EQ(bodies[0].linearVelocity, Vec3(9, 9, 9));
  EXPECT_TRUE(SameBits(bodies[0].angularVelocity, before[0].angularVelocity));
  EXPECT_EQ(bodies[0].pseudoAngular, Vec3(0, 1, 0));
  for (const std::size_t untouched : {1u, 2u, 3u}) {
    EXPECT_TRUE(SameBits(bodies[untouched].linearVelocity, before[untouched].linearVelocity)) << untouched;
    EXPECT_TRUE(SameBits(bodies[untouched].angularVelocity, before[untouched].angularVelocity)) << untouched;
    EXPECT_TRUE(SameBits(bodies[untouched].pseudoLinear, before[untouched].pseudoLinear)) << untouched;
  }
}

// A 2 kg box resting exactly on the ground (depth 0: no Baumgarte bias)
// enters the solver with v = -g h after gravity. Stopping it takes the
// impulse m g h in all, and the four-point block gives each corner the
// least-norm, equal share m g h / 4. Row by row, swept to convergence, the
// corners may split it unevenly but the sum is still m g h. Tolerances:
// round-off on ~0.3 N s (block, one solve) and the 1e-12 m/s convergence
// test times the mass (row by row).
TEST(ContactSolver, PrecomputedRowsGiveARestingBoxTheImpulseMgh) {
  const double mass = 2.0;
  for (const bool block : {true, false}) {
    WorldSettings settings{.gravity = {0.0, -kG, 0.0}, .sleeping = false};
    settings.methods.blockSolver = block;
    settings.methods.velocityTolerance = 1e-12;
    settings.methods.maxVelocityIterations = 1000;
    ContactScene scene(settings);
    scene.AddPlane({});
    const int box = scene.AddBox({0, 0.5, 0}, Vec3::Constant(0.5), mass);
    scene.Step(kH);
    ASSERT_EQ(scene.Contacts().size(), 1u);
    const Contact& contact = scene.Contacts()[0];
    ASSERT_EQ(contact.manifold.pointCount, 4);
    double total = 0.0;
    for (int i = 0; i < 4; ++i) {
      const double lambda = contact.normalImpulse[static_cast<std::size_t>(i)];
      total += lambda;
      if (block) {
        EXPECT_NEAR(lambda, mass * kG * kH / 4.0, 1e-14) << i;
      }
      // Nothing slides, so friction takes nothing.
      EXPECT_LT(contact.frictionImpulse[static_cast<std::size_t>(i)].norm(), 1e-12) << i;
    }
    EXPECT_NEAR(total, mass * kG * kH, block ? 1e-14 : 1e-11) << "block " << block;
    EXPECT_LT(scene.Body(box).linearVelocity.norm(), block ? 1e-14 : 1e-11);
  }
}

}  // namespace solver_body_test
}  // namespace talus
