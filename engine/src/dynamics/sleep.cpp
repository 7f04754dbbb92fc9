// Islands by union-find and whole-island sleeping; see dynamics/sleep.h.
#include "dynamics/sleep.h"

#include <algorithm>
#include <limits>

namespace talus {

int SleepManager::Find(int body) {
  // Path halving keeps the trees flat without recursion.
  while (m_parent[static_cast<std::size_t>(body)] != body) {
    const std::size_t b = static_cast<std::size_t>(body);
    m_parent[b] = m_parent[static_cast<std::size_t>(m_parent[b])];
    body = m_parent[b];
  }
  return body;
}

void SleepManager::Union(int a, int b) {
  const int ra = Find(a);
  const int rb = Find(b);
  if (ra == rb) return;
  // The smaller index becomes the root: the same forest for any contact order.
  if (ra < rb) {
    m_parent[static_cast<std::size_t>(rb)] = ra;
  } else {
    m_parent[static_cast<std::size_t>(ra)] = rb;
  }
}

int SleepManager::Update(std::span<BodySim> bodies, std::span<SleepState> states,
                         std::span<const Contact> contacts, const WorldSettings& settings, double h) {
  const std::size_t count = bodies.size();
  const double linear2 = settings.sleepLinearVelocity * settings.sleepLinearVelocity;
  const double angular2 = settings.sleepAngularVelocity * settings.sleepAngularVelocity;

  // Rest timers of awake dynamic bodies.
  for (std::size_t i = 0; i < count; ++i) {
    const BodySim& body = bodies[i];
    if (body.type != BodyType::Dynamic || !body.awake) continue;
    const bool resting = states[i].allowSleep && body.linearVelocity.squaredNorm() <= linear2 &&
                         body.angularVelocity.squaredNorm() <= angular2;
    states[i].restTime = resting ? states[i].restTime + h : 0.0;
  }

  m_parent.resize(count);
  for (std::size_t i = 0; i < count; ++i) m_parent[i] = static_cast<int>(i);
  for (const Contact& contact : contacts) {
    const BodySim& a = bodies[static_cast<std::size_t>(contact.bodyA)];
    const BodySim& b = bodies[static_cast<std::size_t>(contact.bodyB)];
    const bool dynamicA = a.type == BodyType::Dynamic;
    const bool dynamicB = b.type == BodyType::Dynamic;
    if (dynamicA && dynamicB) {
      Union(contact.bodyA, contact.bodyB);
      continue;
    }
    // A body carried by a moving kinematic body is not at rest.
    if (dynamicA && b.type == BodyType::Kinematic && (b.linearVelocity.any() || b.angularVelocity.any())) {
      states[static_cast<std::size_t>(contact.bodyA)].restTime = 0.0;
    }
    if (dynamicB && a.type == BodyType::Kinematic && (a.linearVelocity.any() || a.angularVelocity.any())) {
      states[static_cast<std::size_t>(contact.bodyB)].restTime = 0.0;
    }
  }

  // The least rest time of each island decides for all of it.
  m_islandMinRest.assign(count, std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < count; ++i) {
    if (bodies[i].type != BodyType::Dynamic) continue;
    const std::size_t root = static_cast<std::size_t>(Find(static_cast<int>(i)));
    m_islandMinRest[root] = std::min(m_islandMinRest[root], states[i].restTime);
  }
  int awakeIslands = 0;
  for (std::size_t i = 0; i < count; ++i) {
    BodySim& body = bodies[i];
    if (body.type != BodyType::Dynamic) continue;
    const std::size_t root = static_cast<std::size_t>(Find(static_cast<int>(i)));
    const bool sleep = m_islandMinRest[root] >= settings.timeToSleep;
    if (root == i && !sleep) ++awakeIslands;
    if (sleep) {
      body.awake = false;
      body.linearVelocity.setZero();
      body.angularVelocity.setZero();
    } else if (!body.awake) {
      body.awake = true;
      states[i].restTime = 0.0;
    }
  }
  return awakeIslands;
}

}  // namespace talus
