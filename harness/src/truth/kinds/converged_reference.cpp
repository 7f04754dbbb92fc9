// Converged reference: no closed form. The truth is the same backend run
// at timeStep / timeStepDivisor (the runner makes that finer run and
// compares the two trajectories, run_metrics.h), so the evaluator here has
// nothing to judge. The finer run's step count is bounded like any run's.
#include "support/text_util.h"
#include "talus/harness/scenario/scenario_limits.h"
#include "truth/kinds/kind_support.h"

namespace talus::harness {
std::string_view ConvergedReferenceTruth::Schema() {
  return R"json({
  "required": [
    "timeStepDivisor"
  ],
  "properties": {
    "body": {
      "type": "string"
    },
    "timeStepDivisor": {
      "type": "integer",
      "minimum": 2,
      "maximum": 1024
    }
  }
})json";
}

Result<ConvergedReferenceTruth> ConvergedReferenceTruth::Read(TruthReader& reader) {
  const int divisor = reader.Integer("timeStepDivisor");
  if (static_cast<long long>(reader.world.steps) * divisor > kMaxSteps) {
    return reader.Refuse(
        "/timeStepDivisor",
        Concat({"the finer run takes ", std::to_string(reader.world.steps), " x ", std::to_string(divisor),
                " steps, more than the limit of ", std::to_string(kMaxSteps)}));
  }
  return ConvergedReferenceTruth{divisor};
}

void ConvergedReferenceTruth::Write(TruthWriter& writer) const {
  writer.out["timeStepDivisor"] = timeStepDivisor;
}

std::vector<MetricResult> ConvergedReferenceTruth::Evaluate(const Run&, const Truth&,
                                                            const ConvergedReferenceTruth&,
                                                            const Trajectory&) {
  return {};  // the runner compares against the finer run
}

}  // namespace talus::harness
