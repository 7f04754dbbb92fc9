// Free fall: the centre of mass height along the up axis against the
// closed forms a correct integrator of constant gravity produces (truths.h):
// the parabola y0 + v0 t - g t^2 / 2 (any scheme exact for a constant force:
// RK4, velocity Verlet, Talus's ExactConstantAcceleration), symplectic
// Euler's sequence (the write-up's integrator, Bullet's, ODE's, MuJoCo's
// Euler), and explicit Euler's. The three sit g h t / 2 apart, far beyond
// round-off, so a wrong gravity, a wrong start or a drift fails all three;
// which integrator a backend uses is not judged here (the projectile truth
// and the sweeps weigh the integrator's own error). The run is judged
// against the one form it follows best over all its samples, at the sample
// where it strays furthest from that form, so a deviation anywhere in the
// run is reported, not only at its end. Samples after `until` (a landing)
// are not judged.
#include <array>
#include <cassert>
#include <cmath>

#include "talus/harness/analytic/truths.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {
namespace {

enum class FreeFallForm { Parabola, SymplecticEuler, ExplicitEuler };
constexpr std::array<FreeFallForm, 3> kForms = {FreeFallForm::SymplecticEuler, FreeFallForm::Parabola,
                                                FreeFallForm::ExplicitEuler};

double FormHeight(FreeFallForm form, const FreeFallTruth& kind, double h, const Sample& sample) {
  switch (form) {
    case FreeFallForm::Parabola:
      return FreeFallHeight(kind.y0, kind.v0, kind.g, sample.time);
    case FreeFallForm::SymplecticEuler:
      return FreeFallHeightSymplecticEuler(kind.y0, kind.v0, kind.g, h, sample.step);
    case FreeFallForm::ExplicitEuler:
      return FreeFallHeightExplicitEuler(kind.y0, kind.v0, kind.g, h, sample.step);
  }
  return NAN;
}

// The metric of the run against one form: its worst sample.
MetricResult WorstAgainst(FreeFallForm form, const Run& run, const Truth& truth, const FreeFallTruth& kind,
                          const Trajectory& trajectory, double* worst) {
  const Vec3 up = UpAxis(run);
  MetricResult metric = MakeMetric("free_fall.height", "m");
  *worst = -1.0;
  for (const Sample& sample : trajectory.samples) {
    if (sample.time > kind.until) break;
    const double height = sample.bodies[static_cast<std::size_t>(truth.body)].centerOfMass.dot(up);
    const double expected = FormHeight(form, kind, trajectory.timeStep, sample);
    const double deviation = std::abs(height - expected);
    // !(deviation <= worst) also picks a NaN height, so it is not hidden.
    if (!(deviation <= *worst)) {
      *worst = std::isnan(deviation) ? INFINITY : deviation;
      metric.measured = height;
      metric.truth = FreeFallHeight(kind.y0, kind.v0, kind.g, sample.time);
      metric.truthIntegrator = expected;
    }
  }
  return metric;
}

}  // namespace

std::string_view FreeFallTruth::Schema() {
  return R"json({
  "required": [
    "body",
    "y0",
    "v0",
    "g"
  ],
  "properties": {
    "body": {
      "type": "string"
    },
    "y0": {
      "type": "number"
    },
    "v0": {
      "type": "number"
    },
    "g": {
      "type": "number",
      "exclusiveMinimum": 0
    },
    "until": {
      "type": "number",
      "exclusiveMinimum": 0,
      "description": "seconds: judge only the samples up to this time (the flight before a landing); default the whole run"
    }
  }
})json";
}

Result<FreeFallTruth> FreeFallTruth::Read(TruthReader& reader) {
  FreeFallTruth fall{reader.Number("y0"), reader.Number("v0"), reader.Number("g")};
  if (reader.Has("until")) fall.until = reader.Number("until");
  return fall;
}

void FreeFallTruth::Write(TruthWriter& writer) const {
  writer.out["y0"] = y0;
  writer.out["v0"] = v0;
  writer.out["g"] = g;
  if (std::isfinite(until)) writer.out["until"] = until;
}

std::vector<MetricResult> FreeFallTruth::Evaluate(const Run& run, const Truth& truth,
                                                  const FreeFallTruth& kind, const Trajectory& trajectory) {
  assert(truth.body >= 0);
  MetricResult best;
  double bestWorst = INFINITY;
  bool first = true;
  // Symplectic Euler first: on a tie (only possible for an empty or
  // one-sample run) the write-up's form is named.
  for (const FreeFallForm form : kForms) {
    double worst = 0.0;
    MetricResult metric = WorstAgainst(form, run, truth, kind, trajectory, &worst);
    if (first || worst < bestWorst) {
      best = metric;
      bestWorst = worst;
      first = false;
    }
  }
  Judge(best, truth.tolerance);
  return {best};
}

}  // namespace talus::harness
