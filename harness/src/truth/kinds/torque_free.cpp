// Torque-free spin: the relative drift of the world angular momentum
// vector, max |L(t) - L(0)| / |L(0)| over all samples with L = I_world w
// about the centre of mass, and of the rotational kinetic energy, max
// |E(t) - E(0)| / E(0). Both truths are 0 and the continuous invariants
// are those of the truth's inertia and omega (torque_free_motion.h); the
// tolerance's relative part bounds both drifts. An engine without the
// gyroscopic term keeps w fixed in the world while I_world turns, so L
// drifts by the order of the inertia's anisotropy: this check catches it.
#include <algorithm>
#include <cassert>

#include "talus/harness/analytic/torque_free_motion.h"
#include "talus/harness/support/nan_extremes.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {

std::string_view TorqueFreeTruth::Schema() {
  return R"json({
  "required": [
    "body",
    "inertia",
    "omega"
  ],
  "properties": {
    "body": {
      "type": "string"
    },
    "inertia": {
      "type": "array",
      "items": {
        "type": "number",
        "exclusiveMinimum": 0
      },
      "minItems": 3,
      "maxItems": 3,
      "description": "kg m^2, principal moments about the body axes x, y, z"
    },
    "omega": {
      "type": "array",
      "items": {
        "type": "number"
      },
      "minItems": 3,
      "maxItems": 3,
      "description": "rad/s, initial angular velocity in the body frame"
    }
  }
})json";
}

Result<TorqueFreeTruth> TorqueFreeTruth::Read(TruthReader& reader) {
  auto spin = ReadSpinStart(reader);
  if (!spin) return spin.GetError();
  return TorqueFreeTruth{spin.Value().inertia, spin.Value().omega};
}

void TorqueFreeTruth::Write(TruthWriter& writer) const {
  writer.Vector("inertia", inertia);
  writer.Vector("omega", omega);
}

std::vector<MetricResult> TorqueFreeTruth::Evaluate(const Run& run, const Truth& truth,
                                                    const TorqueFreeTruth& kind,
                                                    const Trajectory& trajectory) {
  (void)run;
  assert(truth.body >= 0);
  const auto body = static_cast<std::size_t>(truth.body);
  const SpinInvariants invariants = ComputeSpinInvariants(kind.inertia, kind.omega);
  const BodyReading& first = trajectory.samples.front().bodies[body];
  const Vec3 momentum0 = first.worldInertia * first.angularVelocity;
  double momentumDrift = 0.0;
  double energyDrift = 0.0;
  for (const Sample& sample : trajectory.samples) {
    const BodyReading& state = sample.bodies[body];
    const Vec3 momentum = state.worldInertia * state.angularVelocity;
    const double energy = 0.5 * state.angularVelocity.dot(momentum);
    momentumDrift = MaxKeepingNaN(momentumDrift, (momentum - momentum0).norm() / invariants.angularMomentum);
    energyDrift = MaxKeepingNaN(energyDrift, std::abs(energy - invariants.energy) / invariants.energy);
  }
  // Drifts are fractions; the allowed one is the tolerance's relative part
  // (its absolute part, also a fraction here, adds to it).
  const Tolerance allowed{.absolute = truth.tolerance.absolute + truth.tolerance.relative, .relative = 0.0};
  MetricResult momentum = MakeMetric("torque_free.angular_momentum_drift", "");
  momentum.measured = momentumDrift;
  momentum.truth = 0.0;
  Judge(momentum, allowed);
  MetricResult energy = MakeMetric("torque_free.energy_drift", "");
  energy.measured = energyDrift;
  energy.truth = 0.0;
  Judge(energy, allowed);
  return {momentum, energy};
}

}  // namespace talus::harness
