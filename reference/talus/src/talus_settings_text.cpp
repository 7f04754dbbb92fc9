// A Talus row's settings list (talus_settings_text.h): each engine setting
// as text, with the scenario's default and the effect beside every
// departure. The strings are what results.json records for the row.
#include "talus_settings_text.h"

#include <algorithm>
#include <string>
#include <utility>

#include "talus/broad_phase.h"
#include "talus/reference/setting_text.h"
#include "talus_enum_names.h"

namespace talus::reference {
namespace {

using harness::Run;

// A setting of the engine as text: `value` is this row's, `scenarioDefault`
// the engine's default as the scenario poses it (ScenarioSettings). When the
// row departs from it, the default and `effect` (why, and what it measurably
// changes) are recorded beside it.
harness::Setting Choice(std::string key, std::string value, std::string scenarioDefault, std::string effect) {
  if (value == scenarioDefault) return {std::move(key), std::move(value)};
  return {std::move(key), std::move(value), std::move(scenarioDefault), std::move(effect)};
}

const char* OnOff(bool on) { return on ? "on" : "off"; }

std::string SolverText(const WorldSettings& s) {
  if (s.methods.stepSolver == StepSolver::SoftStep) {
    const SoftStepSettings& soft = s.methods.softStep;
    return "soft step: " + std::to_string(soft.substeps) + " sub-steps, contacts at " +
           SettingNumber(soft.contactHertz) + " Hz (at most a quarter of the sub-step rate), damping ratio " +
           SettingNumber(soft.dampingRatio) + ", push-out " + SettingNumber(soft.pushOutSpeed) +
           " m/s; the sweep settings below are unused";
  }
  return ContactSolverText(s.methods.contactOrder);
}

std::string ExtraSweepsText(const WorldSettings& s) {
  if (s.methods.maxVelocityIterations <= s.velocityIterations) return "none";
  return "up to " + std::to_string(s.methods.maxVelocityIterations) + " sweeps, until changes < " +
         SettingNumber(s.methods.velocityTolerance) + " m/s";
}

std::string ReuseText(double distance) { return distance > 0.0 ? SettingNumber(distance) : "off"; }

std::string PersistenceText(const NarrowPhaseSettings& n) {
  return n.persistence == ManifoldPersistence::Accumulate ? SettingNumber(n.persistenceDistance) : "off";
}

std::string SpeculativeMarginText(const WorldSettings& s) {
  const std::string fixed = SettingNumber(s.methods.narrowPhase.speculativeMargin);
  if (!s.methods.speculativeMotion) return fixed + " (fixed)";
  return fixed + ", or the pair's reach this step where larger (h (|v| + |w| rho + g h) of each body)";
}

std::string BroadPhaseText(const Run& run, const WorldSettings& s) {
  return s.methods.forceBroadPhase
             ? std::string(BroadPhaseName(s.broadPhase)) +
                   ", forced in every world (scenario world.broadPhase \"" +
                   harness::BroadPhaseChoiceName(run.scenario.world.broadPhase) + "\")"
             : std::string(BroadPhaseName(s.broadPhase)) + "; brute force in worlds of at most " +
                   std::to_string(kTinyWorldBodies) + " bodies (engine default)";
}

// The row, its step and the solver that runs it.
void AddStepping(const Run& run, std::string_view variantName, const WorldSettings& s,
                 const WorldSettings& base, std::vector<harness::Setting>& out) {
  out.insert(
      out.end(),
      {
          {"engine", "Talus (double)"},
          {"variant", std::string(variantName)},
          {"time step (s)", SettingNumber(run.timeStep)},
          {"stepping", "World::Step(h), one step per Step()"},
          Choice("integrator", TranslationText(s.methods.translation),
                 TranslationText(base.methods.translation),
                 "the write-up's symplectic Euler: free flight lags the parabola by g h t / 2 "
                 "(docs/dynamics.md, "
                 "\"Translation exact for constant gravity\")"),
          Choice(
              "solver", SolverText(s), SolverText(base),
              s.methods.stepSolver == StepSolver::SoftStep
                  ? "the soft step: soft contact springs over sub-steps instead of sweeps with Baumgarte's "
                    "push "
                    "(docs/dynamics.md, \"The soft step\")"
                  : "the coloured order, whose colours split across threads with bit-identical results: the "
                    "same rows in another order, so results differ from the pair order by the order "
                    "(docs/dynamics.md, \"The coloured wide solver\")"),
          {"velocity iterations",
           std::to_string(s.velocityIterations) + (run.iterations > 0 ? "" : " (engine default)")},
      });
}

// How the sweeps solve the contacts and correct positions.
void AddSolver(const WorldSettings& s, const WorldSettings& base, std::vector<harness::Setting>& out) {
  out.insert(
      out.end(),
      {
          Choice("warm starting", OnOff(s.methods.warmStarting), OnOff(base.methods.warmStarting),
                 "the write-up's: every step's solve starts from zero impulses, so a stack carries its load "
                 "only "
                 "after many sweeps"),
          Choice(
              "block solver (a pair's normal rows together)", OnOff(s.methods.blockSolver),
              OnOff(base.methods.blockSolver),
              "the write-up's row by row: the first corner solved takes more load, and a 10-box column sways "
              "7.9 cm where the defaults hold it to 1e-14 m (docs/dynamics.md, \"Measured\")"),
          Choice(
              "friction solve", FrictionSolveText(s.methods.frictionSolve),
              FrictionSolveText(base.methods.frictionSolve),
              "the per-point rows (the write-up's; the only ones the coloured solver and the row-by-row "
              "normals have): a stopping box keeps about 0.6 of its slip a sweep instead of stopping in one "
              "(box_slide at 1/30 s, 5 sweeps: 2.6e-5 m short and rocking; docs/dynamics.md, \"Coupled "
              "block\")"),
          Choice(
              "shock propagation", OnOff(s.methods.shockPropagation), OnOff(base.methods.shockPropagation),
              "the sweeps alone: a load on supports of a tenth of its mass or less is carried only after "
              "many steps, and meanwhile drives them into the ground and is thrown back (a 1000 kg slab on "
              "two 1 kg boxes drifts 0.7 m; docs/dynamics.md, \"Shock propagation\")"),
          Choice("extra velocity sweeps for new contacts", ExtraSweepsText(s), ExtraSweepsText(base),
                 "the write-up's fixed sweep count: a new stack's first solve is left unconverged (a cold "
                 "10-box "
                 "column needs about 150 sweeps not to sag by 1 mm; docs/dynamics.md, \"Constraints\")"),
          Choice("position correction", PositionCorrectionName(s.methods.positionCorrection),
                 PositionCorrectionName(base.methods.positionCorrection),
                 "Bullet's split impulses: the push-out moves positions only, so it adds no kinetic energy "
                 "(a box "
                 "started 5 cm deep leaves at < 1e-3 m/s instead of > 0.3 m/s; docs/dynamics.md, "
                 "\"Constraints\")"),
          {"position iterations", s.methods.positionCorrection == PositionCorrection::Baumgarte
                                      ? "unused"
                                      : std::to_string(s.positionIterations)},
          {"baumgarte factor", SettingNumber(s.baumgarte)},
          {"slop (m)", SettingNumber(s.slop)},
          {"restitution threshold (m/s)", SettingNumber(s.restitutionThreshold)},
          Choice("bounce timing", BounceTimingText(s.methods.bounceTiming),
                 BounceTimingText(base.methods.bounceTiming),
                 "the write-up's: the impact is taken at the step's boundary, so a 1 m drop at 60 Hz lands "
                 "up to "
                 "a step early or late and its apex errs by up to (1 + e^2) v h (docs/dynamics.md, \"Bounces "
                 "timed inside the step\")"),
      });
}

// The combine rules, the broad phase and the narrow phase.
void AddCollision(const Run& run, const WorldSettings& s, const WorldSettings& base,
                  std::vector<harness::Setting>& out) {
  const NarrowPhaseSettings& n = s.methods.narrowPhase;
  const NarrowPhaseSettings& bn = base.methods.narrowPhase;
  out.insert(
      out.end(),
      {
          {"friction combine", harness::CombineRuleName(run.scenario.world.frictionCombine)},
          {"restitution combine", harness::CombineRuleName(run.scenario.world.restitutionCombine)},
          {"broad phase", BroadPhaseText(run, s)},
          Choice("SAT", SatText(n.satMode), SatText(bn.satMode),
                 "the write-up's search of all 2F + E^2 axes: the same contacts for more work "
                 "(docs/collision-narrow-phase.md)"),
          Choice("SAT cache", OnOff(n.useSatCache), OnOff(bn.useSatCache),
                 "the write-up describes the cache but did not build it: every pair searched from scratch"),
          Choice(
              "manifold reuse (m of relative motion)", ReuseText(n.reuseDistance),
              ReuseText(bn.reuseDistance),
              "the write-up runs the narrow phase on every pair every step (docs/collision-narrow-phase.md)"),
          Choice(
              "manifolds", ManifoldText(n.manifoldMode), ManifoldText(bn.manifoldMode),
              "the write-up's points: vertices near the contact plane with one depth for the whole manifold "
              "(docs/collision-narrow-phase.md)"),
          Choice("persistent points (m break distance)", PersistenceText(n), PersistenceText(bn),
                 "the write-up keeps only the points of the step (docs/collision-narrow-phase.md)"),
          Choice("speculative margin (m)", SpeculativeMarginText(s), SpeculativeMarginText(base),
                 "the write-up's fixed margin: a corner that lands within the step sinks in and is pushed "
                 "out (at "
                 "1/30 s tall_box_tipping 15 degrees 4.4e-4 -> 0.18 tolerances, hull_rest 4e-14 -> 0.54; "
                 "docs/testbed-sweeps.md)"),
      });
}

// The bodies: rotation, damping, sleeping, threads, shapes and mass.
void AddBodies(const WorldSettings& s, const WorldSettings& base, std::vector<harness::Setting>& out) {
  out.insert(
      out.end(),
      {
          Choice(
              "gyroscopic term", GyroscopicText(s.methods.rotation), GyroscopicText(base.methods.rotation),
              "the second-order splitting, the write-up's order of accuracy: L still kept, the energy error "
              "O((h w)^2), 36 times the fourth order's at 1/30 s on gazebo_boxes (docs/dynamics.md, "
              "\"Rotation\")"),
          {"damping", "none"},
          {"sleeping", OnOff(s.sleeping)},
          s.threads == 1 ? harness::Setting{"threads", "1"}
                         : harness::Setting{"threads", std::to_string(s.threads), "1",
                                            "the step's broad-phase proxies, narrow phase and integration "
                                            "spread over the threads; results bit-identical, wall time only"},
          {"hull shapes", "talus::BuildHull on the scenario points, in the body frame"},
          {"mass properties",
           "from talus::reference::ComputeBodyMass (exact), body frame, centre of mass at the centroid"},
      });
}

// Listed only where the scenario uses them, so other runs' records stay as they were.
void AddScenarioExtras(const Run& run, std::vector<harness::Setting>& out) {
  if (!run.scenario.loads.empty() || !run.scenario.impulses.empty()) {
    out.push_back({"loads and impulses",
                   "World::ApplyForce (at a point) or ApplyForceToCenter and ApplyTorque before each "
                   "step, scaled by the step's share of the window; World::ApplyLinearImpulse at the "
                   "impulse's step"});
  }
  if (std::any_of(run.scenario.bodies.begin(), run.scenario.bodies.end(),
                  [](const harness::BodySpec& b) { return b.motion == harness::Motion::Kinematic; })) {
    out.push_back({"kinematic bodies",
                   "BodyType::Kinematic with the prescribed velocities: moved by them each step, "
                   "infinite mass to contacts"});
  }
}

}  // namespace

std::vector<harness::Setting> TalusSettingsText(const Run& run, std::string_view variantName,
                                                const WorldSettings& s, const WorldSettings& base) {
  std::vector<harness::Setting> out;
  AddStepping(run, variantName, s, base, out);
  AddSolver(s, base, out);
  AddCollision(run, s, base, out);
  AddBodies(s, base, out);
  AddScenarioExtras(run, out);
  return out;
}

}  // namespace talus::reference
