// What the truth kinds' units (harness/src/truth/kinds/<kind>.cpp) share:
// the scenario model, the trajectory, judging (truth_check.h), JSON, and the
// reading checks more than one kind makes. Evaluators read sample steps and
// times from the trajectory, never assuming stride 1.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "talus/harness/backend/trajectory.h"
#include "talus/harness/scenario/scenario.h"
#include "talus/harness/scenario/truth_kind_io.h"
#include "talus/harness/truth/truth_check.h"

namespace talus::harness {

/// Relative agreement asked of a truth's copy of a body's values (a spin
/// truth's inertia and omega, a projectile's start) with the body they
/// describe: values written to ~7 significant digits pass.
inline constexpr double kSpinConsistencyTolerance = 1e-6;

/// The written reason of the truth's secondary bound `field` (e.g.
/// "maxJitter"); empty when the truth has none (one built in code). An
/// evaluator gives it to the metric the bound judges.
std::string BoundReason(const Truth& truth, std::string_view field);

/// A free-body truth (projectile, drifts) holds only while nothing but
/// gravity acts: the refusal when some body is static.
std::optional<Error> RefuseStaticBodies(const TruthReader& reader, const std::string& kind);

/// Drifts are relative: the body (or, for energy without a body, some
/// dynamic body) must start moving (spinning, for a spin drift), else there
/// is nothing to divide by. The refusal, when not.
std::optional<Error> RefuseStillStart(const TruthReader& reader, const std::string& kind, bool spin);

/// A spin truth's principal moments and body-frame omega, checked against
/// its body: a dynamic box (its frame is principal), moments in the box's
/// proportions, omega the body's angularVelocity seen from the body.
struct SpinStart {
  Vec3 inertia;
  Vec3 omega;
};
Result<SpinStart> ReadSpinStart(const TruthReader& reader);

/// The body indices a truth lists by name in `field` (an array of
/// strings), in file order: each must name a dynamic body, once. Absent
/// field: every dynamic body.
Result<std::vector<int>> ReadDynamicBodies(const TruthReader& reader, const char* field);

/// A time window [from, until] in seconds read from the optional fields
/// `fromField` (default 0) and `untilField` (default the end of the run):
/// refused when it does not lie inside the run or is empty.
struct TimeWindow {
  double from = 0.0;
  double until = 0.0;
};
Result<TimeWindow> ReadTimeWindow(const TruthReader& reader, const char* fromField, const char* untilField);

/// Refuses a tolerance without an absolute part: for a metric whose truth
/// is 0 (a drift, an excess, a shortfall) a relative part allows nothing.
std::optional<Error> RequireAbsoluteTolerance(const TruthReader& reader, std::string_view unit);

/// The angle (radians, in [0, pi]) of the rotation from a to b.
double RotationAngle(const Quat& a, const Quat& b);

}  // namespace talus::harness
