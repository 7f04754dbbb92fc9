// World: owns the bodies and steps them forward in time.
//
// Bodies live in contiguous arrays inside the World and are named by
// BodyId{index, generation}; ids of destroyed bodies are detected and
// refused. Every call that takes user data validates it first and either
// applies it completely or returns an Error and leaves the world exactly as
// it was: a bad step size or a NaN force never reaches the state.
//
// One World::Step(dt) runs the write-up's pipeline (see
// engine/src/world/world_step.cpp): external forces and velocity
// integration, collision, the sequential impulse solve, position
// integration, then sleeping and statistics.
#pragma once

#include <memory>
#include <variant>
#include <vector>

#include "talus/body.h"
#include "talus/result.h"
#include "talus/step_statistics.h"
#include "talus/world_settings.h"

namespace talus {

/// The success value of an operation that returns nothing else.
using Status = Result<std::monostate>;

struct WorldData;

class World {
 public:
  /// A world with default settings.
  World();
  /// A world with `settings`, or an Error naming the invalid setting.
  static Result<World> Create(const WorldSettings& settings);

  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  World(const World&) = delete;
  World& operator=(const World&) = delete;
  ~World();

  [[nodiscard]] const WorldSettings& Settings() const;
  /// Replaces the settings; refused (nothing changes) when one is invalid.
  Status SetSettings(const WorldSettings& settings);

  /// Creates a body from `def`; refused with an Error naming the field when a
  /// number is NaN or infinite, the mass is not > 0, the inertia is not
  /// symmetric positive definite, the orientation is zero, or friction or
  /// restitution are out of range.
  Result<BodyId> CreateBody(const BodyDef& def);
  /// Destroys a body and every contact it had; refused for a stale id.
  Status DestroyBody(BodyId id);
  /// Whether `id` names a live body.
  [[nodiscard]] bool IsValid(BodyId id) const;
  /// Number of live bodies.
  [[nodiscard]] int BodyCount() const;
  /// Ids of all live bodies in slot order.
  [[nodiscard]] std::vector<BodyId> BodyIds() const;

  /// A copy of the body's state; refused for a stale id.
  [[nodiscard]] Result<BodyState> GetBodyState(BodyId id) const;

  /// Moves the body frame to `position` (metres) and `orientation`
  /// (normalised; must be non-zero) and wakes it.
  Status SetTransform(BodyId id, const Vec3& position, const Quat& orientation);
  /// Sets the centre-of-mass velocity (m/s); ignored by static bodies.
  Status SetLinearVelocity(BodyId id, const Vec3& velocity);
  /// Sets the angular velocity (rad/s, world space); ignored by static bodies.
  Status SetAngularVelocity(BodyId id, const Vec3& velocity);
  /// Adds a force (N, world space) at a world point (metres) for the next
  /// step only; wakes the body. Ignored by non-dynamic bodies.
  Status ApplyForce(BodyId id, const Vec3& force, const Vec3& worldPoint);
  /// Adds a force (N) at the centre of mass for the next step; wakes the body.
  Status ApplyForceToCenter(BodyId id, const Vec3& force);
  /// Adds a torque (N m, world space) for the next step; wakes the body.
  Status ApplyTorque(BodyId id, const Vec3& torque);
  /// Changes momentum at once by `impulse` (N s) applied at `worldPoint`.
  Status ApplyLinearImpulse(BodyId id, const Vec3& impulse, const Vec3& worldPoint);
  /// Changes angular momentum at once by `impulse` (N m s, world space).
  Status ApplyAngularImpulse(BodyId id, const Vec3& impulse);

  /// Advances the world by `dt` seconds (finite, > 0). Refused, with nothing
  /// changed, for a bad dt. Returns what the step did and skipped.
  Result<StepStatistics> Step(double dt);

  /// Internal state for the engine's own stages (engine/src/world); not part
  /// of the stable API.
  [[nodiscard]] WorldData& Data() { return *m_data; }
  [[nodiscard]] const WorldData& Data() const { return *m_data; }

 private:
  explicit World(std::unique_ptr<WorldData> data);
  std::unique_ptr<WorldData> m_data;
};

}  // namespace talus
