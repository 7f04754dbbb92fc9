// The Talus rows' variant policy (talus_variants.h): the scenario's
// settings on WorldSettings{}, then each variant's named differences.
#include "talus_variants.h"

#include <string>

namespace talus::reference {
namespace {

using harness::CombineRule;
using harness::Run;

Result<FrictionCombine> ToFrictionCombine(CombineRule rule) {
  switch (rule) {
    case CombineRule::Sqrt:
      return FrictionCombine::GeometricMean;
    case CombineRule::Min:
      return FrictionCombine::Min;
    case CombineRule::Max:
      return FrictionCombine::Max;
    case CombineRule::Multiply:
      return FrictionCombine::Product;
    case CombineRule::Average:
      return FrictionCombine::Average;
  }
  return Error{"unknown friction combine rule"};
}

Result<RestitutionCombine> ToRestitutionCombine(CombineRule rule) {
  switch (rule) {
    case CombineRule::Max:
      return RestitutionCombine::Max;
    case CombineRule::Min:
      return RestitutionCombine::Min;
    case CombineRule::Multiply:
      return RestitutionCombine::Product;
    case CombineRule::Average:
      return RestitutionCombine::Average;
    case CombineRule::Sqrt:
      break;
  }
  return Error{std::string("restitution combine \"") + harness::CombineRuleName(rule) +
               "\" has no Talus rule (max, min, multiply, average)"};
}

// What the scenario states, on top of WorldSettings{}: the user's choices
// (gravity, iterations, combine rules, sleeping off as the peers run, the
// gyroscopic term, the broad phase, the bounce timing when the file names
// one) and the thread count of the run. The `talus` row is exactly this.
WorldSettings ScenarioSettings(const Run& run, FrictionCombine friction, RestitutionCombine restitution,
                               const TalusBackendOptions& options) {
  WorldSettings settings;
  settings.threads = options.threads;
  settings.gravity = run.scenario.world.gravity;
  if (run.iterations > 0) {
    settings.velocityIterations = run.iterations;
    settings.positionIterations = run.iterations;
  }
  settings.frictionCombine = friction;
  settings.restitutionCombine = restitution;
  settings.sleeping = false;
  // The scenario's gyroscopic term: on, the engine's default rotation;
  // off, the write-up's constant rate.
  if (!run.scenario.world.gyroscopic) settings.methods.rotation = RotationIntegrator::ConstantRate;
  // The scenario's broad phase: auto keeps the engine's default (the grid,
  // brute force in tiny worlds); any other choice runs in every world.
  switch (run.scenario.world.broadPhase) {
    case harness::BroadPhaseChoice::Auto:
      break;
    case harness::BroadPhaseChoice::UniformGrid:
      settings.broadPhase = BroadPhaseKind::UniformGrid;
      settings.methods.forceBroadPhase = true;
      break;
    case harness::BroadPhaseChoice::AabbTree:
      settings.broadPhase = BroadPhaseKind::AabbTree;
      settings.methods.forceBroadPhase = true;
      break;
    case harness::BroadPhaseChoice::BruteForce:
      settings.broadPhase = BroadPhaseKind::BruteForce;
      settings.methods.forceBroadPhase = true;
      break;
  }
  // The scenario's bounce timing; auto keeps the engine's default.
  switch (run.scenario.world.bounceTiming) {
    case harness::BounceTimingChoice::Auto:
      break;
    case harness::BounceTimingChoice::TimeOfImpact:
      settings.methods.bounceTiming = BounceTiming::TimeOfImpact;
      break;
    case harness::BounceTimingChoice::StepBoundary:
      settings.methods.bounceTiming = BounceTiming::StepBoundary;
      break;
  }
  return settings;
}

// The write-up's choices (docs/write-up.md) in place of each improvement
// the engine's defaults carry; the scenario's own choices stay, but for a
// bounce timing left to auto, which is the write-up's step boundary.
void ApplyWriteUp(const Run& run, WorldSettings& settings) {
  if (run.scenario.world.gyroscopic) {
    // The second-order splitting: the write-up has no gyroscopic term, and
    // the scenario asks for one; the least of the engine's.
    settings.methods.rotation = RotationIntegrator::MomentumSplitting;
  }
  if (run.scenario.world.bounceTiming == harness::BounceTimingChoice::Auto) {
    settings.methods.bounceTiming = BounceTiming::StepBoundary;
  }
  settings.methods.translation = TranslationIntegrator::SymplecticEuler;
  settings.methods.narrowPhase.satMode = SatMode::Full;
  settings.methods.narrowPhase.manifoldMode = ManifoldMode::WriteUp;
  settings.methods.narrowPhase.useSatCache = false;
  settings.methods.narrowPhase.reuseDistance = 0.0;                       // the narrow phase every step
  settings.methods.narrowPhase.persistence = ManifoldPersistence::Fresh;  // and only its points
  settings.methods.speculativeMotion = false;                             // a fixed speculative margin
  settings.methods.warmStarting = false;
  // Plain row-by-row Gauss-Seidel, a fixed number of sweeps (a cap below
  // the iteration count means no extra sweeps), friction per point.
  settings.methods.blockSolver = false;
  settings.methods.maxVelocityIterations = 1;
  settings.methods.frictionSolve = FrictionSolve::PerPoint;
  settings.methods.shockPropagation = false;  // the sweeps alone
}

// The variant's settings: the scenario's on WorldSettings{}, then the
// variant's named differences (listed in docs/testbed-backends.md, "The
// Talus rows", and in each row's settings as engine-default departures).
WorldSettings MakeSettings(const WorldSettings& base, const Run& run, Variant variant) {
  WorldSettings settings = base;
  switch (variant) {
    case Variant::Defaults:
      break;
    case Variant::WriteUp:
      ApplyWriteUp(run, settings);
      break;
    case Variant::SplitImpulses:
      settings.methods.positionCorrection = PositionCorrection::SplitImpulses;
      break;
    case Variant::Coloured:
      // The coloured order, with the friction rows it has (no coupled block).
      settings.methods.contactOrder = ContactOrder::ByColour;
      settings.methods.frictionSolve = FrictionSolve::PerPoint;
      break;
    case Variant::Soft:
      // The soft step (docs/dynamics.md, "The soft step") at the engine's
      // 4 sub-steps; the run's iterations are a sweep count, which this
      // solver does not have. Its friction rows are per point (it has no
      // coupled block).
      settings.methods.stepSolver = StepSolver::SoftStep;
      settings.methods.frictionSolve = FrictionSolve::PerPoint;
      break;
    case Variant::ManifoldFriction:
      // Friction as the manifold's three rows (docs/dynamics.md, "Friction
      // per manifold") in place of the coupled block and per-point rows.
      settings.methods.frictionSolve = FrictionSolve::PerManifold;
      break;
    case Variant::CoupledFriction:
      // The coupled block on every face, the default before Adaptive
      // (docs/dynamics.md, "Adaptive friction"): Adaptive's other half.
      settings.methods.frictionSolve = FrictionSolve::CoupledBlock;
      break;
  }
  return settings;
}

}  // namespace

const char* VariantName(Variant variant) {
  switch (variant) {
    case Variant::Defaults:
      return "talus";
    case Variant::WriteUp:
      return "talus-writeup";
    case Variant::SplitImpulses:
      return "talus-split";
    case Variant::Coloured:
      return "talus-coloured";
    case Variant::Soft:
      return "talus-soft";
    case Variant::ManifoldFriction:
      return "talus-manifold";
    case Variant::CoupledFriction:
      return "talus-coupled";
  }
  return "talus";
}

Result<RowSettings> ConfigureRow(const Run& run, Variant variant, const TalusBackendOptions& options) {
  const std::string prefix = std::string(VariantName(variant)) + ": ";
  auto friction = ToFrictionCombine(run.scenario.world.frictionCombine);
  if (!friction) return Error{prefix + friction.GetError().message};
  auto restitution = ToRestitutionCombine(run.scenario.world.restitutionCombine);
  if (!restitution) return Error{prefix + restitution.GetError().message};
  RowSettings row;
  row.base = ScenarioSettings(run, friction.Value(), restitution.Value(), options);
  row.settings = MakeSettings(row.base, run, variant);
  return row;
}

Result<WorldSettings> TalusRowSettings(const harness::Run& run, std::string_view row,
                                       const TalusBackendOptions& options) {
  for (const Variant variant : kVariants) {
    if (row != VariantName(variant)) continue;
    auto configured = ConfigureRow(run, variant, options);
    if (!configured) return configured.GetError();
    return configured.Value().settings;
  }
  // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive)
  // on "..." + std::string(row) here.
  std::string message = "\"";
  message += row;
  message +=
      "\" is not a Talus row (talus, talus-writeup, talus-split, talus-coloured, talus-soft, "
      "talus-manifold, talus-coupled)";
  return Error{message};
}

}  // namespace talus::reference
