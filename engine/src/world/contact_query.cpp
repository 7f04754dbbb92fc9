// World::GetContactPoints (talus/world.h, talus/contact_query.h): a copy of
// the World's contact list, which world_step.cpp keeps sorted by pair key
// for warm starting.
#include "talus/contact_query.h"

#include "talus/world.h"
#include "world/world_data.h"

namespace talus {

std::vector<ContactPointInfo> World::GetContactPoints() const {
  const WorldData& data = *m_data;
  std::vector<ContactPointInfo> points;
  for (const Contact& contact : data.contacts) {
    const BodyId bodyA{contact.bodyA, data.records[static_cast<std::size_t>(contact.bodyA)].generation};
    const BodyId bodyB{contact.bodyB, data.records[static_cast<std::size_t>(contact.bodyB)].generation};
    for (int p = 0; p < contact.manifold.pointCount; ++p) {
      const ContactPoint& point = contact.manifold.points[static_cast<std::size_t>(p)];
      points.push_back({bodyA, bodyB, point.position, contact.manifold.normal, point.depth, contact.friction,
                        contact.restitution});
    }
  }
  return points;
}

}  // namespace talus
