// Reading back the contacts of a World: the points the last World::Step
// found and handed to the solver, for tools (the testbed, debug drawing)
// that must see them through the public API.
//
// The list is a copy, made on request; the step never builds it. Pairs come
// in the World's pair-key order (body A's index, then B's), points in
// manifold order, so the same world state always gives the same list.
#pragma once

#include <vector>

#include "talus/body.h"
#include "talus/math.h"

namespace talus {

class World;

/// One contact point of the last step.
struct ContactPointInfo {
  BodyId bodyA;                  ///< the body the normal points towards
  BodyId bodyB;                  ///< the other body
  Vec3 position = Vec3::Zero();  ///< metres, world space, midway between the surfaces
  Vec3 normal = Vec3::UnitY();   ///< unit, world space, from B towards A
  double depth = 0.0;            ///< metres, > 0 when penetrating (< 0 within a speculative margin)
  double friction = 0.0;         ///< the pair's combined Coulomb coefficient
  double restitution = 0.0;      ///< the pair's combined restitution
};

/// Every contact point the last World::Step found (empty before the first
/// step, and after a body of a pair was destroyed).
std::vector<ContactPointInfo> GetContactPoints(const World& world);

}  // namespace talus
