// The scenario model: what a scenario file (scenarios/<family>/<name>.json,
// format in docs/scenarios.md) means once parsed, validated and expanded.
//
// Every value here has passed the schema and the semantic checks of the
// loader (harness/src/scenario/, scenario_mapping.cpp and the section
// mappings beside it): numbers are finite, quaternions unit length, dynamic
// bodies have a positive mass or density, names are unique and every truth
// names an existing body. Conventions: SI units, +y is up when gravity is the
// default, quaternions are (w, x, y, z) in the file and Eigen's Quaterniond
// here.
#pragma once

#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "talus/harness/scenario/truth_kinds.h"
#include "talus/math.h"

namespace talus::harness {

/// How two bodies' coefficients combine into the pair's value.
enum class CombineRule {
  Sqrt,      ///< sqrt(a * b): the project's friction rule
  Min,       ///< min(a, b)
  Max,       ///< max(a, b): the project's restitution rule
  Multiply,  ///< a * b: Bullet's built-in rule for both
  Average,   ///< (a + b) / 2
};

/// The combined coefficient of a pair under `rule`.
double Combine(CombineRule rule, double a, double b);

/// The rule's name as written in scenario files ("sqrt", "min", ...).
const char* CombineRuleName(CombineRule rule);

/// Which broad-phase structure Talus runs (file: world.broadPhase). Auto is
/// the engine's default: the uniform grid, with brute force in worlds of
/// at most 128 bodies, where it is faster; each other choice runs that
/// structure in every world (talus::MethodSettings::forceBroadPhase), as the
/// write-up's figure 2 needs on a 15-body scene. Every structure finds the
/// same pairs, so results do not change, only the work counted. The peers
/// keep their own broad phases (listed in their settings).
enum class BroadPhaseChoice { Auto, UniformGrid, AabbTree, BruteForce };

/// The choice's name as written in scenario files ("auto", "uniform_grid",
/// "aabb_tree", "brute_force").
const char* BroadPhaseChoiceName(BroadPhaseChoice choice);

/// When Talus times a bounce (file: world.bounceTiming). Auto is each Talus
/// variant's own: the engine's default (talus::BounceTiming::TimeOfImpact)
/// for "talus", "talus-split" and "talus-coloured", the impact at the step's
/// boundary for "talus-writeup". The peers keep their own contact handling.
enum class BounceTimingChoice { Auto, TimeOfImpact, StepBoundary };

/// The choice's name as written in scenario files ("auto",
/// "time_of_impact", "step_boundary").
const char* BounceTimingChoiceName(BounceTimingChoice choice);

/// World settings shared by every body.
struct WorldSpec {
  Vec3 gravity = Vec3(0.0, -9.81, 0.0);  ///< m/s^2
  double timeStep = 1.0 / 60.0;          ///< seconds, in (0, 1]
  int iterations = 0;                    ///< solver iterations; 0 = the engine's own default
  int steps = 1;                         ///< number of steps to run (file: seconds or steps), >= 1
  CombineRule frictionCombine = CombineRule::Sqrt;
  CombineRule restitutionCombine = CombineRule::Max;
  /// Integrate the gyroscopic term w x (I w), each engine in its implicit
  /// form (Talus WorldSettings::gyroscopic, Bullet
  /// BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY, ODE dBodySetGyroscopicMode).
  /// Default true: without it a torque-free body keeps w (not L) constant.
  bool gyroscopic = true;
  /// Talus's broad-phase structure (see BroadPhaseChoice). Default Auto.
  BroadPhaseChoice broadPhase = BroadPhaseChoice::Auto;
  /// Talus's bounce timing (see BounceTimingChoice). Default Auto.
  BounceTimingChoice bounceTiming = BounceTimingChoice::Auto;
  bool operator==(const WorldSpec&) const = default;
};

/// A box centred on the body origin.
struct BoxShape {
  Vec3 halfExtents = Vec3::Ones();  ///< metres, each > 0
  bool operator==(const BoxShape&) const = default;
};
/// A sphere centred on the body origin.
struct SphereShape {
  double radius = 1.0;  ///< metres, > 0
  bool operator==(const SphereShape&) const = default;
};
/// The convex hull of points given in the body frame. The body origin is
/// the frame the points are written in, not necessarily the centre of mass.
struct HullShape {
  std::vector<Vec3> points;  ///< metres, at least 4, spanning a volume
  bool operator==(const HullShape&) const = default;
};
using ShapeSpec = std::variant<BoxShape, SphereShape, HullShape>;

/// How a body moves. A kinematic body follows its prescribed velocity
/// (BodySpec::linearVelocity, angularVelocity, constant) whatever touches
/// it: infinite mass to contacts, no gravity, no loads (a conveyor, a
/// moving platform).
enum class Motion { Static, Dynamic, Kinematic };

/// One body of a scenario.
struct BodySpec {
  std::string name;  ///< unique within the scenario
  ShapeSpec shape;
  Motion motion = Motion::Dynamic;
  Vec3 position = Vec3::Zero();         ///< metres, of the body origin
  Quat orientation = Quat::Identity();  ///< unit
  Vec3 linearVelocity = Vec3::Zero();   ///< m/s, of the centre of mass (kinematic: prescribed, of the origin)
  Vec3 angularVelocity = Vec3::Zero();  ///< rad/s, world frame (kinematic: prescribed)
  double density = 0.0;                 ///< kg/m^3; > 0 when mass is 0 (dynamic bodies)
  double mass = 0.0;                    ///< kg; > 0 when density is 0 (dynamic bodies)
  double friction = 0.5;                ///< Coulomb coefficient, >= 0
  double restitution = 0.0;             ///< in [0, 1]
};

/// The frame a load's force and torque are written in.
enum class LoadFrame {
  World,  ///< fixed world axes
  Body,   ///< the body's axes: the vector turns with the body
};

/// A force and a torque applied to a dynamic body over the window
/// [start, end) seconds (the file's "loads" list, docs/scenarios.md). Each
/// step [t, t + h) applies them scaled by the share of the step inside the
/// window (AppliedLoadShare in applied_loads.h), so the impulse delivered
/// is exactly force x (end - start) whatever the time step; a body-frame
/// vector is turned by the body's orientation at the step's start.
struct AppliedLoad {
  int body = -1;               ///< index into Scenario::bodies, a dynamic body
  Vec3 force = Vec3::Zero();   ///< N, in `frame`
  Vec3 torque = Vec3::Zero();  ///< N m, in `frame`, about the centre of mass
  LoadFrame frame = LoadFrame::World;
  /// Where the force acts, metres in the body frame (from the body origin);
  /// none: at the centre of mass. Off the centre it adds (p - c) x force.
  std::optional<Vec3> point = std::nullopt;
  double start = 0.0;                                    ///< seconds, >= 0
  double end = std::numeric_limits<double>::infinity();  ///< seconds, > start; infinity = the run's end
  bool operator==(const AppliedLoad&) const = default;
};

/// A linear impulse (N s, world frame) given to a dynamic body at once at
/// the start of the step nearest `time` (the file's "impulses" list):
/// the centre of mass's velocity changes by linear / m and, applied at a
/// point off the centre of mass, the angular velocity by I^-1 (p - c) x
/// linear.
struct AppliedImpulse {
  int body = -1;               ///< index into Scenario::bodies, a dynamic body
  Vec3 linear = Vec3::Zero();  ///< N s, world frame
  /// Metres in the body frame (from the body origin); none: the centre of mass.
  std::optional<Vec3> point = std::nullopt;
  double time = 0.0;  ///< seconds, in [0, the run's duration)
  bool operator==(const AppliedImpulse&) const = default;
};

/// Quantities a run records (the file's "measure" list).
enum class Quantity { Position, Orientation, Velocity, Energy, Momentum, Contacts, Penetration };

/// How close a measurement must be to its truth: it passes when
/// |measured - truth| <= absolute + relative * |truth|. Every truth of a
/// scenario file has one (the loader refuses a truth without, or with both
/// parts zero), with the physical reason for its size beside it
/// (Truth::toleranceReason).
struct Tolerance {
  double absolute = 0.0;  ///< in the truth's unit
  double relative = 0.0;  ///< fraction
  bool operator==(const Tolerance&) const = default;
};

/// A figure published for the same case (e.g. by the benchmark's authors),
/// printed beside the measured one; never judged.
struct PublishedFigure {
  double value = 0.0;                                       ///< the figure, or the low end of a range
  double upper = std::numeric_limits<double>::quiet_NaN();  ///< the high end of a range, NaN for one figure
  std::string source;                                       ///< who measured it, how
};

/// A backend for which a truth is a known failure, with the physical reason
/// (the file's "ungated" list): its metrics are still measured, judged and
/// reported, but do not fail `talus-testbed check` for that backend.
struct UngatedBackend {
  std::string backend;  ///< registry name, e.g. "talus-writeup"
  std::string reason;   ///< why it fails, with the measured figure
  bool operator==(const UngatedBackend&) const = default;
};

struct Truth {
  TruthKind kind;
  int body = -1;  ///< index into Scenario::bodies, -1 when the truth is about the whole world
  Tolerance tolerance;
  /// Why the tolerance has its size: the physics it allows for (time-step
  /// error, slop, solver convergence); the file's tolerance "reason".
  std::string toleranceReason{};
  /// Whether the truth's metrics count in the CI check (MetricResult::checked)
  /// for every backend. False for a known shortfall of every engine: still
  /// measured, judged and reported, but not failing the gate; the
  /// reason is gateReason. Default true.
  bool gate = true;
  /// Why the truth is out of the gate for every backend (the file's
  /// "gateReason", required when gate is false, refused otherwise).
  std::string gateReason{};
  /// The written reason of each secondary bound the truth's kind reads
  /// (TruthReader::Bound: maxLateral, maxJitter, ...), keyed by the field's
  /// name: the file writes each bound as {"value", "reason"}.
  std::map<std::string, std::string> boundReasons{};
  /// Backends for which this truth is outside the gate, each with its
  /// reason (no repeats). Default none.
  std::vector<UngatedBackend> ungated{};
  /// The published figure for this truth's metric, when there is one.
  std::optional<PublishedFigure> published = std::nullopt;
};

/// One scenario, fully resolved (sweeps already applied).
struct Scenario {
  std::string name;
  std::string description;
  std::string file;  ///< where it was read from ("" when parsed from text)
  WorldSpec world;
  std::vector<BodySpec> bodies;  ///< at least one
  /// Backends (registry names) the scenario runs on, file order, no
  /// duplicates; empty (the default) = every backend the runner is given.
  /// Names are checked against the registry by the runner, which runs the
  /// intersection with its own list (runner.h).
  std::vector<std::string> backends;
  /// Quantities to record; the optional metrics (energy and momentum drift,
  /// penetration, contacts) are computed only when listed.
  std::vector<Quantity> measure;
  std::vector<Truth> truths;
  /// Forces and torques on dynamic bodies (the file's "loads"), file order.
  std::vector<AppliedLoad> loads{};
  /// Impulses on dynamic bodies (the file's "impulses"), file order.
  std::vector<AppliedImpulse> impulses{};
};

/// One resolved value of a sweep parameter.
struct SweepValue {
  std::string name;  ///< the sweep's name, e.g. "mu"
  std::string
      value;  ///< the sweep's label for it, else its compact JSON (first entry for perTarget), e.g. "0.3"
};

/// One run: a scenario with its sweep values applied, plus the stepping the
/// backend must use (which a runner may change, e.g. for a converged
/// reference at a smaller time step).
struct Run {
  std::string id;  ///< scenario name plus sweep values, e.g. "box_slide[mu=0.3,v0=2]"
  Scenario scenario;
  std::vector<SweepValue> sweepValues;
  double timeStep = 1.0 / 60.0;  ///< seconds
  int iterations = 0;            ///< 0 = the engine's own default
  int steps = 1;
};

}  // namespace talus::harness
