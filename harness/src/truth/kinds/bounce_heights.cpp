// Bounce heights: the apex of the body's lowest point after each bounce
// against e^(2k) h (truths.h). The floor level is not in the truth; it is
// where the lowest point starts minus h. The lowest point of the shape at a
// sample is its support point along -up. A bounce is a sample where the
// vertical velocity turns from negative to positive; its apex is the
// highest lowest point before the velocity turns negative again. With a
// stride > 1 the apex is known to within the stride's travel (documented in
// docs/testbed-runner.md). An apex the run never reached measures NaN and
// fails.
//
// Each apex is judged with the file's tolerance alone, the same at every
// step: an engine that times its impacts inside the step (Talus) owes the
// apex to round-off and the slop-sized push-out of its contact. Beside each
// apex a reported-only metric (bounce_heights.apexK.step_allowance, no
// tolerance: not judged, not in the sweep's error) gives its step
// resolution (ApexStepResolution): a time-stepped engine that finds an
// impact only at a step's end may find it up to one step late or early, so
// the rebound starts up to v_j h away from the floor and from a speed up to
// g h off the impact speed v_j, moving apex j by up to (1 + e^2) v_j h;
// later apexes carry it on scaled by e^2 per bounce. It says how much of a
// step-resolved engine's error its time step explains; it forgives none.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <string>

#include "talus/harness/analytic/truths.h"
#include "talus/harness/support/nan_extremes.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {
namespace {

// Height along `up` of the lowest point of `shape` placed at `state`.
double LowestPoint(const ShapeSpec& shape, const BodyReading& state, const Vec3& up) {
  const Vec3 localDown = state.orientation.conjugate() * Vec3(-up);
  Vec3 support = Vec3::Zero();
  if (const auto* box = std::get_if<BoxShape>(&shape)) {
    const Vec3& h = box->halfExtents;
    support = Vec3(localDown.x() >= 0 ? h.x() : -h.x(), localDown.y() >= 0 ? h.y() : -h.y(),
                   localDown.z() >= 0 ? h.z() : -h.z());
  } else if (const auto* sphere = std::get_if<SphereShape>(&shape)) {
    support = localDown.normalized() * sphere->radius;
  } else {
    const auto& points = std::get<HullShape>(shape).points;
    double best = -std::numeric_limits<double>::infinity();
    for (const Vec3& p : points) {
      if (p.dot(localDown) > best) {
        best = p.dot(localDown);
        support = p;
      }
    }
  }
  return (state.origin + state.orientation * support).dot(up);
}

// Metres: how far apex k (from 1) may sit from e^(2k) h because impacts are
// resolved to one step dt: sum over bounces j <= k of
// e^(2 (k - j)) (1 + e^2) v_j dt, with impact speeds v_j = e^(j-1) sqrt(2 g h).
double ApexStepResolution(double h, double e, double g, double dt, int k) {
  double resolution = 0.0;
  double impactSpeed = std::sqrt(2.0 * g * h);
  for (int j = 1; j <= k; ++j) {
    resolution = e * e * resolution + (1.0 + e * e) * impactSpeed * dt;
    impactSpeed *= e;
  }
  return resolution;
}

}  // namespace

std::string_view BounceHeightsTruth::Schema() {
  return R"json({
  "required": [
    "body",
    "h",
    "e",
    "count"
  ],
  "properties": {
    "body": {
      "type": "string"
    },
    "h": {
      "type": "number",
      "exclusiveMinimum": 0
    },
    "e": {
      "type": "number",
      "minimum": 0,
      "maximum": 1
    },
    "count": {
      "type": "integer",
      "minimum": 1,
      "maximum": 100
    }
  }
})json";
}

Result<BounceHeightsTruth> BounceHeightsTruth::Read(TruthReader& reader) {
  return BounceHeightsTruth{reader.Number("h"), reader.Number("e"), reader.Integer("count")};
}

void BounceHeightsTruth::Write(TruthWriter& writer) const {
  writer.out["h"] = h;
  writer.out["e"] = e;
  writer.out["count"] = count;
}

std::vector<MetricResult> BounceHeightsTruth::Evaluate(const Run& run, const Truth& truth,
                                                       const BounceHeightsTruth& kind,
                                                       const Trajectory& trajectory) {
  assert(truth.body >= 0);
  const auto body = static_cast<std::size_t>(truth.body);
  const ShapeSpec& shape = run.scenario.bodies[body].shape;
  const Vec3 up = UpAxis(run);
  const double floor = LowestPoint(shape, trajectory.samples.front().bodies[body], up) - kind.h;

  std::vector<double> apexes;
  bool rising = false;
  bool fell = false;
  double apex = 0.0;
  for (const Sample& sample : trajectory.samples) {
    const BodyReading& state = sample.bodies[body];
    const double speed = state.linearVelocity.dot(up);
    if (!rising && fell && speed > 0.0) {
      rising = true;
      apex = -std::numeric_limits<double>::infinity();
    }
    if (rising) {
      apex = MaxKeepingNaN(apex, LowestPoint(shape, state, up) - floor);
      if (speed < 0.0) {
        apexes.push_back(apex);
        rising = false;
        if (static_cast<int>(apexes.size()) == kind.count) break;
      }
    }
    if (speed < 0.0) fell = true;
  }

  const std::vector<double> expected = BounceApexHeights(kind.h, kind.e, kind.count);
  std::vector<MetricResult> metrics;
  for (int k = 0; k < kind.count; ++k) {
    MetricResult metric = MakeMetric("bounce_heights.apex" + std::to_string(k + 1), "m");
    metric.measured = k < static_cast<int>(apexes.size()) ? apexes[static_cast<std::size_t>(k)]
                                                          : std::numeric_limits<double>::quiet_NaN();
    metric.truth = expected[static_cast<std::size_t>(k)];
    Judge(metric, truth.tolerance);
    metrics.push_back(metric);
    MetricResult allowance = MakeMetric(metric.name + ".step_allowance", "m");
    allowance.measured =
        ApexStepResolution(kind.h, kind.e, run.scenario.world.gravity.norm(), trajectory.timeStep, k + 1);
    allowance.truth = 0.0;
    Judge(allowance, Tolerance{});  // reported, never judged
    metrics.push_back(allowance);
  }
  return metrics;
}

}  // namespace talus::harness
