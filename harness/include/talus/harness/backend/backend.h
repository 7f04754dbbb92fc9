// The backend interface: one physics engine (Talus, Bullet, ODE...) behind
// one door, so the runner can build the same run in each, step it and read
// the same quantities back.
//
// A backend object is a built world: a factory takes a Run and returns either
// a complete world or an Error (bad shape, unsupported feature), never a
// half-built one. Body indices are the scenario's body order. Every engine
// setting a backend chooses (solver, tolerances, margins, combine rules...)
// is listed by Settings() so each run records what it measured with.
// Conventions: contact normals point from body B towards body A and depth is
// positive when the bodies overlap (docs/ARCHITECTURE.md vocabulary).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "talus/harness/scenario/scenario.h"
#include "talus/math.h"
#include "talus/result.h"

namespace talus::harness {

/// One body's state as the engine reports it.
struct BodyReading {
  Vec3 centerOfMass = Vec3::Zero();     ///< metres, world
  Vec3 origin = Vec3::Zero();           ///< metres, world: where the scenario's body frame is now
  Quat orientation = Quat::Identity();  ///< of the scenario's body frame
  Vec3 linearVelocity = Vec3::Zero();   ///< m/s, of the centre of mass
  Vec3 angularVelocity = Vec3::Zero();  ///< rad/s, world frame
  double mass = 0.0;                    ///< kg; 0 for static bodies
  Mat3 worldInertia = Mat3::Zero();     ///< kg m^2 about the centre of mass, world axes; 0 for static
};

/// One contact point as the engine reports it.
struct ContactReading {
  int bodyA = -1;               ///< scenario body index
  int bodyB = -1;               ///< scenario body index
  Vec3 point = Vec3::Zero();    ///< metres, world
  Vec3 normal = Vec3::UnitY();  ///< unit, from B towards A
  double depth = 0.0;           ///< metres, > 0 when penetrating
};

/// One engine setting a run used, for the record ("solver", "sequential impulse").
/// A value that differs from what the engine gives a new user names that
/// default and why it was changed, with its measured effect, so the report
/// can list every departure from the engine's defaults.
struct Setting {
  std::string key;
  std::string value;
  /// The engine's own default when `value` differs from it; "" when `value`
  /// is the engine's default or the setting is not an engine choice.
  std::string engineDefault{};
  /// Why it differs and what it measurably changes ("" when it does not differ).
  std::string effect{};
};

/// One per-step count an engine reports about its own work ("sphere pairs", 12).
struct StepCounter {
  std::string name;
  double value = 0.0;
};

/// Wall-clock seconds one stage of the engine's step took ("FindContacts",
/// 0.004): how an engine that times its own stages says where a step's time
/// went. Times vary run to run; the list of stages does not.
struct StageTiming {
  std::string stage;
  double seconds = 0.0;
};

/// A step counter whose name starts with this prefix says which structure
/// did a piece of work ("structure: uniform grid"): 1 for the one that ran
/// this step, 0 for the others. The report shows these as labels, not as
/// counts in the figure-2 chart.
inline constexpr const char* kStructureCounterPrefix = "structure: ";

class Backend {
 public:
  virtual ~Backend() = default;

  /// The registry name, e.g. "bullet".
  [[nodiscard]] virtual std::string Name() const = 0;
  /// Advances the world by one time step of the run.
  virtual void Step() = 0;
  /// Why the last Step failed: the engine refused the step or reported an
  /// error (Talus's World::Step refusal, ODE's dWorldStep returning 0).
  /// Empty (the default) when it went well. The runner stops a run at the
  /// first failed step and records this reason; a backend whose engine
  /// cannot fail leaves it at the default. Non-finite states need no
  /// override: the runner checks every body after every step.
  [[nodiscard]] virtual std::string StepFailure() const { return {}; }
  [[nodiscard]] virtual int BodyCount() const = 0;
  /// State of scenario body `index` (0 <= index < BodyCount()).
  [[nodiscard]] virtual BodyReading GetBodyState(int index) const = 0;
  /// Contacts found by the last Step (empty before the first).
  [[nodiscard]] virtual std::vector<ContactReading> GetContacts() const = 0;
  /// Every setting this world was built with, in a fixed order.
  [[nodiscard]] virtual std::vector<Setting> Settings() const = 0;
  /// Counts of what the last Step did (bodies, candidate pairs, SAT tests,
  /// contact points...), in a fixed order, for the report's broad-phase
  /// figure; empty (the default) when the engine reports none.
  [[nodiscard]] virtual std::vector<StepCounter> StepCounters() const { return {}; }
  /// The time of each stage of the last Step, in the engine's step order,
  /// the same stages every step; together they cover the engine's step (not
  /// the backend's own work around it). Empty (the default) when the engine
  /// does not time its stages; talus-scenes reports them (bench_run.h).
  [[nodiscard]] virtual std::vector<StageTiming> StageTimings() const { return {}; }
  /// Asks the engine to time its stages from the next Step on (an engine
  /// that can time them may skip the clock reads otherwise). Does nothing
  /// by default.
  virtual void TimeStages() {}
};

/// Whether a backend's worlds may step on several threads at once: declared
/// by the backend where it registers, read by the runner's thread pool.
struct ThreadSafety {
  /// Empty when every world of the backend is independent (it shares no
  /// state with any other world), so its jobs may run on any thread at the
  /// same time. Otherwise the library whose process-wide state its worlds
  /// share ("ode": library-wide state and per-thread collision data;
  /// "bullet": globals such as gContactAddedCallback and the profiler):
  /// every job of every backend naming the same library runs, in order, on
  /// one thread of its own.
  std::string sharedStateOf;

  /// Worlds that share nothing: any thread, any number at once.
  static ThreadSafety Independent() { return {}; }
  /// Worlds that share `library`'s process-wide state: one thread per library.
  static ThreadSafety SharesStateOf(std::string library) { return {std::move(library)}; }
};

/// Builds a world for a run.
using BackendFactory = std::function<Result<std::unique_ptr<Backend>>(const Run&)>;

/// Backends by name. Peers register themselves through a function of their
/// library (RegisterBulletBackends, RegisterOdeBackends...), called by the
/// program that wants them; there is no static self-registration, which
/// static libraries would silently drop.
class BackendRegistry {
 public:
  /// Adds a backend with its thread safety; `name` must be new (asserted).
  void Register(std::string name, std::string description, ThreadSafety safety, BackendFactory factory);
  /// Registered names, sorted.
  [[nodiscard]] std::vector<std::string> Names() const;
  [[nodiscard]] bool Has(std::string_view name) const;
  /// One-line description of a registered backend ("" if unknown).
  [[nodiscard]] std::string Description(std::string_view name) const;
  /// The thread safety a registered backend declared (Independent if unknown).
  [[nodiscard]] ThreadSafety GetThreadSafety(std::string_view name) const;
  /// Builds `run` with the named backend; an unknown name is an Error
  /// listing the known ones.
  [[nodiscard]] Result<std::unique_ptr<Backend>> Create(std::string_view name, const Run& run) const;

 private:
  struct Entry {
    std::string description;
    ThreadSafety safety;
    BackendFactory factory;
  };
  std::map<std::string, Entry, std::less<>> m_entries;
};

/// Whole-world mechanical quantities derived from body states.
struct WorldMeasures {
  double kineticEnergy = 0.0;           ///< J: sum m v^2 / 2 + w^T I w / 2
  double potentialEnergy = 0.0;         ///< J: sum -m g . x (zero at the origin)
  Vec3 linearMomentum = Vec3::Zero();   ///< kg m/s
  Vec3 angularMomentum = Vec3::Zero();  ///< kg m^2/s about the world origin
};

/// Energy and momenta of the dynamic bodies of `backend` under `gravity`.
WorldMeasures MeasureWorld(const Backend& backend, const Vec3& gravity);

}  // namespace talus::harness
