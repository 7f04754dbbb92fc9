// A miniature of the World's step for testing the dynamics alone: bodies as
// BodySim, contacts from manifolds the test computes analytically (box
// corners against planes), and the same engine stages World::Step runs
// (IntegrateVelocities, CarryImpulses, ContactSolver, IntegratePositions),
// in the same order.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "dynamics/body_sim.h"
#include "dynamics/contact.h"
#include "dynamics/contact_solver.h"
#include "dynamics/integrator.h"
#include "talus/pair_query.h"
#include "talus/shape.h"
#include "talus/step_statistics.h"
#include "talus/world_settings.h"

namespace talus::testing {

/// A static plane n . x = offset that boxes rest on (body B of its contacts).
struct GroundPlane {
  Vec3 normal = Vec3::UnitY();
  double offset = 0.0;
  double friction = 0.5;
  double restitution = 0.0;
};

/// A dynamic box of uniform density.
struct TestBox {
  int body = -1;
  Vec3 halfExtents = Vec3::Constant(0.5);
  double friction = 0.5;
  double restitution = 0.0;
};

class ContactScene {
 public:
  /// `margin`: corners closer to a plane than this (metres) become contact
  /// points, with negative depth while apart (speculative contacts). The
  /// default 1 cm keeps resting contacts from flickering; a margin above
  /// the largest v h catches every impact before it penetrates.
  explicit ContactScene(const WorldSettings& settings, double margin = 0.01)
      : m_settings(settings), m_margin(margin) {}

  /// Adds a plane as a static body of its own; returns its body index.
  int AddPlane(const GroundPlane& plane) {
    m_bodies.emplace_back();
    m_planes.push_back({static_cast<int>(m_bodies.size()) - 1, plane});
    return m_planes.back().body;
  }

  /// A box of `mass` kg centred at `center`.
  int AddBox(const Vec3& center, const Vec3& halfExtents, double mass,
             const Quat& orientation = Quat::Identity(), double friction = 0.5, double restitution = 0.0) {
    BodySim body;
    body.type = BodyType::Dynamic;
    body.center = center;
    body.orientation = orientation;
    body.invMass = 1.0 / mass;
    const Vec3 e = 2.0 * halfExtents;
    const Vec3 diag(e.y() * e.y() + e.z() * e.z(), e.x() * e.x() + e.z() * e.z(),
                    e.x() * e.x() + e.y() * e.y());
    body.inertiaLocal = (mass / 12.0 * diag).asDiagonal();
    body.invInertiaLocal = body.inertiaLocal.inverse();
    const PrincipalAxes principal = ComputePrincipalAxes(body.inertiaLocal);
    body.principalFrame = principal.frame;
    body.principalInertia = principal.moments;
    body.UpdateWorldInertia();
    m_bodies.push_back(body);
    m_boxes.push_back({static_cast<int>(m_bodies.size()) - 1, halfExtents, friction, restitution});
    return m_boxes.back().body;
  }

  /// Boxes also collide with each other, through the engine's narrow phase
  /// (CollideShapes, clipped manifolds, this margin); off by default.
  void EnableBoxPairs() { m_boxPairs = true; }
  /// The solver, to set its range runner.
  ContactSolver& Solver() { return m_solver; }
  std::span<const BodySim> Bodies() const { return m_bodies; }

  BodySim& Body(int index) { return m_bodies[static_cast<std::size_t>(index)]; }
  const StepStatistics& LastStats() const { return m_stats; }
  std::span<const Contact> Contacts() const { return m_contacts; }

  /// One step of `h` seconds, in World::Step's order.
  void Step(double h) {
    m_stats = StepStatistics{};
    IntegrateVelocities(m_bodies, m_settings.gravity, h);
    m_previous.swap(m_contacts);
    m_contacts.clear();
    Collide();
    if (m_settings.methods.warmStarting) m_stats.warmStartedPoints = CarryImpulses(m_previous, m_contacts);
    m_solver.Prepare(m_bodies, m_contacts, m_settings, h, m_stats);
    if (m_settings.methods.warmStarting) m_solver.WarmStart();
    m_solver.SolveVelocities(m_settings.velocityIterations, m_settings.methods.maxVelocityIterations,
                             m_settings.methods.velocityTolerance);
    const bool pseudo = m_solver.UsesPseudoVelocities();
    if (pseudo) m_solver.SolveSplitImpulses(m_settings.positionIterations);
    m_solver.Scatter(m_bodies, pseudo);
    m_solver.StoreImpulses(m_contacts);
    IntegratePositions(m_bodies, h, pseudo, m_settings.methods.rotation, m_settings.methods.translation);
  }

  /// Kinetic plus potential energy of all boxes, J.
  double Energy() const {
    double energy = 0.0;
    for (const TestBox& box : m_boxes) {
      const BodySim& b = m_bodies[static_cast<std::size_t>(box.body)];
      const double m = 1.0 / b.invMass;
      const Mat3 r = b.orientation.toRotationMatrix();
      const Mat3 inertia = r * b.inertiaLocal * r.transpose();
      energy += 0.5 * m * b.linearVelocity.squaredNorm() +
                0.5 * b.angularVelocity.dot(inertia * b.angularVelocity) -
                m * m_settings.gravity.dot(b.center);
    }
    return energy;
  }

 private:
  // Every box corner within the margin of (or behind) every plane is a point of
  // the box-plane manifold: normal the plane's (from B, the ground, to A,
  // the box), position midway between corner and plane, feature = corner.
  void Collide() {
    struct Sorter {
      bool operator()(const Contact& a, const Contact& b) const { return a.PairKey() < b.PairKey(); }
    };
    for (const auto& [planeBody, plane] : m_planes) {
      for (const TestBox& box : m_boxes) {
        const BodySim& b = m_bodies[static_cast<std::size_t>(box.body)];
        ContactManifold manifold{};
        manifold.normal = plane.normal;
        manifold.depth = -1e300;
        for (std::uint32_t k = 0; k < 8; ++k) {
          const Vec3 sign((k & 1) ? 1.0 : -1.0, (k & 2) ? 1.0 : -1.0, (k & 4) ? 1.0 : -1.0);
          const Vec3 corner = b.center + b.orientation * sign.cwiseProduct(box.halfExtents);
          const double distance = plane.normal.dot(corner) - plane.offset;
          if (distance > m_margin) continue;
          ContactPoint& point = manifold.points[static_cast<std::size_t>(manifold.pointCount++)];
          point.position = corner - 0.5 * distance * plane.normal;
          point.depth = -distance;
          point.featureId = k;
          manifold.depth = std::max(manifold.depth, point.depth);
        }
        if (manifold.pointCount == 0) continue;
        // The box is A (the normal points at it), the plane is B.
        m_contacts.push_back(
            MakeContact(box.body, planeBody, manifold,
                        MixFriction(box.friction, plane.friction, m_settings.frictionCombine),
                        MixRestitution(box.restitution, plane.restitution, m_settings.restitutionCombine)));
      }
    }
    if (m_boxPairs) CollideBoxPairs();
    std::sort(m_contacts.begin(), m_contacts.end(), Sorter{});
  }

  // Every pair of boxes through the narrow phase; the lower body index is A.
  void CollideBoxPairs() {
    const NarrowPhaseSettings narrow{.speculativeMargin = m_margin};
    for (std::size_t i = 0; i < m_boxes.size(); ++i) {
      for (std::size_t j = i + 1; j < m_boxes.size(); ++j) {
        const TestBox& a = m_boxes[i];
        const TestBox& b = m_boxes[j];
        const BodySim& simA = m_bodies[static_cast<std::size_t>(a.body)];
        const BodySim& simB = m_bodies[static_cast<std::size_t>(b.body)];
        const double reach = a.halfExtents.norm() + b.halfExtents.norm() + m_margin;
        if ((simA.center - simB.center).squaredNorm() > reach * reach) continue;
        const Result<PairContact> pair = CollideShapes(
            Shape::CreateBox(a.halfExtents).Value(), {.position = simA.center, .rotation = simA.orientation},
            Shape::CreateBox(b.halfExtents).Value(), {.position = simB.center, .rotation = simB.orientation},
            narrow);
        if (!pair || !pair.Value().touching) continue;
        const PairContact& found = pair.Value();
        ContactManifold manifold{};
        manifold.normal = found.normal;
        manifold.depth = found.Depth();
        manifold.pointCount = std::min(found.pointCount, kMaxManifoldPoints);
        for (int k = 0; k < manifold.pointCount; ++k) {
          const PairContactPoint& from = found.points[static_cast<std::size_t>(k)];
          ContactPoint& to = manifold.points[static_cast<std::size_t>(k)];
          to.position = from.position;
          to.depth = from.depth;
          to.featureId = from.featureId;
        }
        m_contacts.push_back(MakeContact(
            a.body, b.body, manifold, MixFriction(a.friction, b.friction, m_settings.frictionCombine),
            MixRestitution(a.restitution, b.restitution, m_settings.restitutionCombine)));
      }
    }
  }

  struct PlaneBody {
    int body;
    GroundPlane plane;
  };

  WorldSettings m_settings;
  double m_margin = 0.01;
  bool m_boxPairs = false;
  std::vector<BodySim> m_bodies;
  std::vector<PlaneBody> m_planes;
  std::vector<TestBox> m_boxes;
  std::vector<Contact> m_contacts;
  std::vector<Contact> m_previous;
  ContactSolver m_solver;
  StepStatistics m_stats;
};

}  // namespace talus::testing
