// Stress envelopes (stress.h): the search along an axis, the axes with
// their criteria, the probes that judge one value, and the envelope table.
#include "talus/harness/stress/stress.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "support/numbers.h"
#include "support/text_util.h"
#include "talus/harness/run/runner.h"
#include "talus/harness/sweep/sweep.h"

namespace talus::harness {
namespace {

std::string EnvelopeNumber(double value) {
  if (std::isnan(value)) return "-";
  return FormatNumber(value, 4);
}

bool Finite(const BodyReading& state) {
  return state.centerOfMass.allFinite() && state.linearVelocity.allFinite() &&
         state.angularVelocity.allFinite();
}

// Runs `run` with `backend`, recording every `stride`-th step.
Result<Trajectory> Simulate(const BackendRegistry& registry, const std::string& backend, const Run& run) {
  auto built = registry.Create(backend, run);
  if (!built) return built.GetError();
  const int stride = SampleStride(run.steps, 2000);
  Trajectory trajectory = Record(
      *built.Value(), run, run.steps, run.timeStep,
      [&](int step) { return IsSampled(step, run.steps, stride); }, nullptr);
  if (!trajectory.failure.empty()) return Error{trajectory.failure};
  return trajectory;
}

// Largest horizontal and vertical displacement of the dynamic bodies from
// their start over every sample; NaN when a state is not finite.
std::pair<double, double> MaxDisplacement(const Run& run, const Trajectory& trajectory) {
  double horizontal = 0.0;
  double vertical = 0.0;
  const Sample& first = trajectory.samples.front();
  for (const Sample& sample : trajectory.samples) {
    for (std::size_t b = 0; b < sample.bodies.size(); ++b) {
      if (run.scenario.bodies[b].motion != Motion::Dynamic) continue;
      if (!Finite(sample.bodies[b])) return {kNaN, kNaN};
      const Vec3 d = sample.bodies[b].centerOfMass - first.bodies[b].centerOfMass;
      horizontal = std::max(horizontal, std::hypot(d.x(), d.z()));
      vertical = std::max(vertical, std::abs(d.y()));
    }
  }
  return {horizontal, vertical};
}

// "Stands": every dynamic body stays within `maxHorizontal` and
// `maxVertical` metres of its start at every sample, and nothing is NaN.
EnvelopeProbe Stands(double value, const Run& run, const Trajectory& trajectory, double maxHorizontal,
                     double maxVertical) {
  EnvelopeProbe probe;
  probe.value = value;
  const auto [horizontal, vertical] = MaxDisplacement(run, trajectory);
  probe.measure = horizontal;
  if (std::isnan(horizontal)) {
    probe.detail = "non-finite state";
  } else if (horizontal > maxHorizontal) {
    probe.detail = Concat({"moved ", EnvelopeNumber(horizontal), " m sideways"});
  } else if (vertical > maxVertical) {
    probe.detail = Concat({"moved ", EnvelopeNumber(vertical), " m vertically"});
  }
  probe.pass = probe.detail.empty();
  return probe;
}

}  // namespace

// Geometric walk, then bisection between the last pass and the first fail:
// integer axes halve the interval until the two values are adjacent, real
// axes take `bisections` geometric midpoints (the axes span decades).
EnvelopeResult SearchEnvelope(const EnvelopeSearch& search,
                              const std::function<EnvelopeProbe(double)>& oracle) {
  assert(search.start > 0.0 && search.factor > 0.0 && search.factor != 1.0);
  EnvelopeResult result;
  const bool up = search.factor > 1.0;
  const auto withinLimit = [&](double v) {
    return up ? v <= search.limit * (1 + 1e-12) : v >= search.limit * (1 - 1e-12);
  };
  const auto probe = [&](double v) {
    EnvelopeProbe p = oracle(v);
    p.value = v;
    result.probes.push_back(p);
    return p.pass;
  };
  for (double v = search.start; withinLimit(v);
       v = search.integer ? std::round(v * search.factor) : v * search.factor) {
    if (!probe(v)) {
      result.firstFail = v;
      break;
    }
    result.lastPass = v;
  }
  if (std::isnan(result.firstFail) || std::isnan(result.lastPass)) return result;
  if (search.integer) {
    while (std::abs(result.firstFail - result.lastPass) > 1.0) {
      const double mid = std::floor((result.firstFail + result.lastPass) / 2.0);
      (probe(mid) ? result.lastPass : result.firstFail) = mid;
    }
  } else {
    for (int i = 0; i < search.bisections; ++i) {
      const double mid = std::sqrt(result.firstFail * result.lastPass);
      (probe(mid) ? result.lastPass : result.firstFail) = mid;
    }
  }
  return result;
}

const std::vector<StressAxisInfo>& StressAxes() {
  static const std::vector<StressAxisInfo> axes{
      {StressAxis::Column,
       "column",
       "boxes",
       "stands 10 s: every box within 5 cm of its start horizontally and 1 cm vertically at every sample",
       {2, 2, 16, true, 0},
       {2, 2, 256, true, 0}},
      {StressAxis::MassRatio,
       "mass-ratio",
       "top/bottom",
       "a two-box stack stands 5 s (same criterion as column)",
       {1, 10, 1e3, false, 2},
       {1, 10, 1e6, false, 4}},
      {StressAxis::TimeStep,
       "time-step",
       "s",
       "a 5-layer pyramid stays for 5 s: every box within 5 cm of its start (both directions: the contact "
       "sag grows as g h^2), nothing non-finite",
       {1.0 / 240.0, 2, 1.0 / 15.0, false, 2},
       {1.0 / 960.0, 2, 0.5, false, 4}},
      {StressAxis::Offset,
       "offset",
       "m",
       "box rest (height within 1 cm) and box slide (stop distance within 3 %) moved this far along x and z: "
       "error scalar <= 1",
       {100, 10, 1e5, false, 0},
       {100, 10, 1e8, false, 3}},
      {StressAxis::Speed,
       "speed",
       "m/s",
       "a 0.1 m box launched at a 0.05 m static wall at 1/60 s (no gravity) ends on its own side",
       {1, 2, 256, false, 2},
       {1, 2, 4096, false, 4}},
      {StressAxis::EnergyDrift,
       "energy-drift",
       "steps",
       "a torque-free spinning box keeps its kinetic energy and angular momentum within 1 % of the initial "
       "over "
       "this many 1/60 s steps (rounded)",
       {10, 10, 1e4, false, 2},
       {10, 10, 1e5, false, 4}},
      {StressAxis::SmallSize,
       "small-size",
       "m",
       "a cube of this edge rests (height within 1 % of the edge) and slides (within 3 %): error scalar <= 1",
       {1, 0.1, 0.01, false, 0},
       {1, 0.1, 1e-4, false, 2}},
      {StressAxis::LargeSize,
       "large-size",
       "m",
       "same as small-size, walking up",
       {1, 10, 10, false, 0},
       {1, 10, 1e3, false, 2}},
  };
  return axes;
}

EnvelopeProbe ProbeStress(const BackendRegistry& registry, const std::string& backend, StressAxis axis,
                          double value) {
  EnvelopeProbe probe;
  probe.value = value;
  const std::vector<Run> runs = StressRuns(axis, value);
  if (axis == StressAxis::Offset || axis == StressAxis::SmallSize || axis == StressAxis::LargeSize) {
    RunnerOptions options;
    options.backends = {backend};
    options.deterministic = true;
    double worst = 0.0;
    for (const Run& run : runs) {
      const RunResult result = RunOne(registry, run, backend, options);
      if (!result.error.empty()) {
        probe.detail = Concat({run.id, ": ", result.error});
        return probe;
      }
      const double error = RunErrorScalar(result);
      if (!(error <= 1.0) && probe.detail.empty())
        probe.detail = Concat({run.id, " error ", EnvelopeNumber(error)});
      worst = std::isnan(error) ? std::numeric_limits<double>::infinity() : std::max(worst, error);
    }
    probe.measure = worst;
    probe.pass = probe.detail.empty();
    return probe;
  }
  const Run& run = runs.front();
  auto simulated = Simulate(registry, backend, run);
  if (!simulated) {
    probe.detail = simulated.GetError().message;
    return probe;
  }
  const Trajectory& trajectory = simulated.Value();
  switch (axis) {
    case StressAxis::Column:
    case StressAxis::MassRatio:
      return Stands(value, run, trajectory, 0.05, 0.01);
    case StressAxis::TimeStep:
      return Stands(value, run, trajectory, 0.05, 0.05);
    case StressAxis::Speed: {
      const BodyReading& last = trajectory.samples.back().bodies[1];
      probe.measure = last.centerOfMass.x();
      if (!Finite(last)) {
        probe.detail = "non-finite state";
      } else if (last.centerOfMass.x() > 0.0) {
        probe.detail = Concat({"tunnelled: ended at x = ", EnvelopeNumber(last.centerOfMass.x()), " m"});
      }
      break;
    }
    case StressAxis::EnergyDrift: {
      // Relative drift of the kinetic energy and of the angular momentum
      // (the body stays at the origin, so about the origin is about its
      // centre of mass); the larger is the measure.
      const WorldMeasures& initial = trajectory.samples.front().measures;
      double energy = 0.0;
      double momentum = 0.0;
      for (const Sample& sample : trajectory.samples) {
        const WorldMeasures& m = sample.measures;
        if (!std::isfinite(m.kineticEnergy) || !m.angularMomentum.allFinite()) {
          energy = momentum = kNaN;
          break;
        }
        energy = std::max(energy, std::abs(m.kineticEnergy - initial.kineticEnergy) / initial.kineticEnergy);
        momentum = std::max(
            momentum, (m.angularMomentum - initial.angularMomentum).norm() / initial.angularMomentum.norm());
      }
      probe.measure = std::max(energy, momentum);
      if (std::isnan(energy)) {
        probe.detail = "non-finite state";
      } else if (energy > 0.01) {
        probe.detail = Concat({"kinetic energy drifted by ", EnvelopeNumber(100.0 * energy), " %"});
      } else if (momentum > 0.01) {
        probe.detail = Concat({"angular momentum drifted by ", EnvelopeNumber(100.0 * momentum), " %"});
      }
      break;
    }
    default:
      break;
  }
  probe.pass = probe.detail.empty();
  return probe;
}

std::string StressMarkdown(const std::vector<StressEntry>& entries) {
  std::vector<std::string> axes;
  std::vector<std::string> backends;
  for (const StressEntry& e : entries) {
    if (std::find(axes.begin(), axes.end(), e.axis) == axes.end()) axes.push_back(e.axis);
    if (std::find(backends.begin(), backends.end(), e.backend) == backends.end())
      backends.push_back(e.backend);
  }
  std::ostringstream out;
  out << "## Stability envelope\n\nEach cell: last passing value / first failing value (- : none within the "
         "searched range).\n\n| backend |";
  for (const std::string& axis : axes) out << " " << axis << " |";
  out << "\n|---|";
  for (std::size_t i = 0; i < axes.size(); ++i) out << "---|";
  out << "\n";
  for (const std::string& backend : backends) {
    out << "| " << backend << " |";
    for (const std::string& axis : axes) {
      for (const StressEntry& e : entries) {
        if (e.axis == axis && e.backend == backend) {
          out << " " << EnvelopeNumber(e.envelope.lastPass) << " / " << EnvelopeNumber(e.envelope.firstFail)
              << " |";
        }
      }
    }
    out << "\n";
  }
  out << "\n### Criteria\n\n| axis | unit | pass when |\n|---|---|---|\n";
  for (const StressAxisInfo& info : StressAxes()) {
    if (std::find(axes.begin(), axes.end(), info.name) == axes.end()) continue;
    out << "| " << info.name << " | " << info.unit << " | " << info.criterion << " |\n";
  }
  out << "\n### Probes\n\n| axis | backend | value | pass | measure | why |\n|---|---|---|---|---|---|\n";
  for (const StressEntry& e : entries) {
    for (const EnvelopeProbe& p : e.envelope.probes) {
      out << "| " << e.axis << " | " << e.backend << " | " << EnvelopeNumber(p.value) << " | "
          << (p.pass ? "ok" : "FAIL") << " | " << EnvelopeNumber(p.measure) << " | " << p.detail << " |\n";
    }
  }
  return out.str();
}

}  // namespace talus::harness
