// ContactPointInfo: one contact point of a World as World::GetContactPoints
// reports it, for tools (the testbed, debug drawing) that must see the
// contacts the last step found through the public API.
//
// The list is a copy, made on request (engine/src/world/contact_query.cpp);
// the step never builds it. Pairs come
// in the World's pair-key order (body A's index, then B's), points in
// manifold order, so the same world state always gives the same list.
#pragma once

#include "talus/body.h"
#include "talus/math.h"

namespace talus {

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

}  // namespace talus
