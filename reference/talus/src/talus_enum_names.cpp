// The text of each engine enum value in a Talus row's settings
// (talus_enum_names.h): one switch or choice per enum, nowhere else.
#include "talus_enum_names.h"

namespace talus::reference {

const char* BroadPhaseName(BroadPhaseKind kind) {
  switch (kind) {
    case BroadPhaseKind::UniformGrid:
      return "uniform grid";
    case BroadPhaseKind::AabbTree:
      return "AABB tree";
    case BroadPhaseKind::BruteForce:
      return "brute force";
  }
  return "unknown";
}

const char* PositionCorrectionName(PositionCorrection correction) {
  switch (correction) {
    case PositionCorrection::Baumgarte:
      return "Baumgarte";
    case PositionCorrection::SplitImpulses:
      return "split impulses";
  }
  return "unknown";
}

std::string TranslationText(TranslationIntegrator translation) {
  return translation == TranslationIntegrator::SymplecticEuler
             ? "symplectic Euler (v += h a; x += h v)"
             : "v += h a; x += h (v0 + v) / 2 for a body no impulse touched (exact for constant "
               "acceleration), else x += h v";
}

std::string ContactSolverText(ContactOrder solver) {
  return solver == ContactOrder::PairByPair ? "sequential impulses (scalar, pair order)"
                                            : "sequential impulses, coloured, four pairs per SIMD bundle";
}

std::string FrictionSolveText(FrictionSolve friction) {
  switch (friction) {
    case FrictionSolve::PerPoint:
      return "per point (two rows a point, one after another)";
    case FrictionSolve::CoupledBlock:
      return "coupled block: a sticking pair's normals and friction (slip and spin patterns) solved "
             "together, else per point";
    case FrictionSolve::PerManifold:
      return "per manifold: slip at the centre of pressure inside a disc, and spin about the normal";
    case FrictionSolve::Adaptive:
      return "adaptive: per manifold, and the coupled block on pairs carrying over 50 weights of their "
             "lighter body";
  }
  return "unknown";
}

std::string BounceTimingText(BounceTiming timing) {
  return timing == BounceTiming::TimeOfImpact
             ? "time of impact inside the step (reflected flight to the step's end)"
             : "step boundary (the write-up's)";
}

std::string SatText(SatMode mode) {
  return mode == SatMode::Full ? "full (every face and edge pair)" : "Gauss-map pruned edge pairs";
}

std::string ManifoldText(ManifoldMode mode) {
  return mode == ManifoldMode::WriteUp ? "write-up (vertices near the contact plane, one depth)"
                                       : "clipped incident face, reduced to 4 points";
}

std::string GyroscopicText(RotationIntegrator rotation) {
  switch (rotation) {
    case RotationIntegrator::ConstantRate:
      return "off (MethodSettings::rotation = ConstantRate)";
    case RotationIntegrator::MomentumSplitting:
      return "on (MethodSettings::rotation = MomentumSplitting: L kept, exact rotations about the "
             "principal axes)";
    case RotationIntegrator::MomentumSplittingFourthOrder:
      return "on (MethodSettings::rotation = MomentumSplittingFourthOrder: L kept, exact rotations about "
             "the principal axes, fourth order)";
  }
  return "unknown";
}

}  // namespace talus::reference
