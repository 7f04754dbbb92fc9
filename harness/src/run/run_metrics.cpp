// Drift, penetration, contact and converged-reference metrics (see
// run_metrics.h for the definitions and where each applies).
#include "talus/harness/run/run_metrics.h"
#include "support/numbers.h"
#include "talus/harness/support/nan_extremes.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace talus::harness {
namespace {

MetricResult Reported(const char* name, const char* unit, double measured) {
  MetricResult metric = MakeMetric(name, unit);
  metric.measured = measured;
  metric.truth = 0.0;
  Judge(metric, Tolerance{});
  return metric;
}

// Total mass, centre of mass and the angular momentum about it.
struct SystemState {
  double mass = 0.0;
  Vec3 center = Vec3::Zero();
  Vec3 angularMomentum = Vec3::Zero();
};

SystemState System(const Sample& sample) {
  SystemState system;
  Vec3 moment = Vec3::Zero();
  for (const BodyReading& body : sample.bodies) {
    system.mass += body.mass;
    moment += body.mass * body.centerOfMass;
  }
  if (system.mass > 0.0) system.center = moment / system.mass;
  // L about c = L about the origin - c x P.
  system.angularMomentum =
      sample.measures.angularMomentum - system.center.cross(sample.measures.linearMomentum);
  return system;
}

// The rotation angle (rad, in [0, pi]) between two unit quaternions.
double AngleBetween(const Quat& a, const Quat& b) {
  const double dot = MinKeepingNaN(1.0, std::abs(a.coeffs().dot(b.coeffs())));
  return 2.0 * std::acos(dot);
}

}  // namespace

bool IsClosedSystem(const Run& run) {
  // A kinematic body, a load or an impulse exchanges momentum with the
  // outside as a static body does.
  return run.scenario.loads.empty() && run.scenario.impulses.empty() &&
         std::none_of(run.scenario.bodies.begin(), run.scenario.bodies.end(),
                      [](const BodySpec& body) { return body.motion != Motion::Dynamic; });
}

std::vector<MetricResult> EnergyDrift(const Trajectory& trajectory) {
  assert(!trajectory.samples.empty());
  const auto energy = [](const Sample& s) { return s.measures.kineticEnergy + s.measures.potentialEnergy; };
  const double initial = energy(trajectory.samples.front());
  double drift = 0.0;
  for (const Sample& sample : trajectory.samples)
    drift = MaxKeepingNaN(drift, std::abs(energy(sample) - initial));
  return {Reported("energy.drift", "J", drift),
          Reported("energy.drift_relative", "", initial != 0.0 ? drift / std::abs(initial) : kNaN)};
}

std::vector<MetricResult> MomentumDrift(const Run& run, const Trajectory& trajectory) {
  assert(!trajectory.samples.empty());
  const Sample& first = trajectory.samples.front();
  const SystemState initial = System(first);
  const Vec3& gravity = run.scenario.world.gravity;
  double linear = 0.0;
  double angular = 0.0;
  for (const Sample& sample : trajectory.samples) {
    const Vec3 expected = first.measures.linearMomentum + initial.mass * gravity * (sample.time - first.time);
    linear = MaxKeepingNaN(linear, (sample.measures.linearMomentum - expected).norm());
    angular = MaxKeepingNaN(angular, (System(sample).angularMomentum - initial.angularMomentum).norm());
  }
  return {Reported("momentum.linear_drift", "N s", linear),
          Reported("momentum.angular_drift", "kg m^2/s", angular)};
}

MetricResult MaxPenetration(const Trajectory& trajectory) {
  double deepest = 0.0;
  for (const Sample& sample : trajectory.samples) deepest = MaxKeepingNaN(deepest, sample.maxPenetration);
  return Reported("penetration.max", "m", deepest);
}

MetricResult FinalContacts(const Trajectory& trajectory) {
  assert(!trajectory.samples.empty());
  return Reported("contacts.final", "", static_cast<double>(trajectory.samples.back().contactCount));
}

std::vector<MetricResult> CompareWithReference(const Truth& truth, const Trajectory& trajectory,
                                               const Trajectory& reference) {
  double position = 0.0;
  double angle = 0.0;
  int matched = 0;
  std::size_t r = 0;
  for (const Sample& sample : trajectory.samples) {
    while (r < reference.samples.size() && reference.samples[r].time < sample.time - 1e-9) ++r;
    if (r == reference.samples.size()) break;
    const Sample& other = reference.samples[r];
    if (std::abs(other.time - sample.time) > 1e-9) continue;
    ++matched;
    for (std::size_t b = 0; b < sample.bodies.size(); ++b) {
      if (truth.body >= 0 && static_cast<int>(b) != truth.body) continue;
      position = MaxKeepingNaN(position, (sample.bodies[b].origin - other.bodies[b].origin).norm());
      angle = MaxKeepingNaN(angle, AngleBetween(sample.bodies[b].orientation, other.bodies[b].orientation));
    }
  }
  MetricResult positionMetric = MakeMetric("converged_reference.position", "m");
  positionMetric.measured = matched > 0 ? position : kNaN;
  positionMetric.truth = 0.0;
  Judge(positionMetric, truth.tolerance);
  MetricResult angleMetric = Reported("converged_reference.orientation", "rad", matched > 0 ? angle : kNaN);
  return {positionMetric, angleMetric};
}

}  // namespace talus::harness
