// MethodSettings: the laboratory's switches. Each selects how the step does
// a piece of its work (which position correction, which integrator, which
// sweep order, which friction solve, which step solver) and keeps the
// original write-up's method selectable beside the measured improvement
// (docs/write-up.md; docs/dynamics.md gives each alternative's figures).
// They are not tunables a user of the engine needs: the defaults are the
// engine the testbed validates (its `talus` row runs WorldSettings{}
// unchanged), and the testbed's named variants (talus-writeup, talus-split,
// talus-coloured, talus-soft, talus-manifold; docs/testbed-backends.md) are
// the ones that change them. WorldSettings::methods holds one; combinations
// in which a switch would do nothing are refused by World::Create.
#pragma once

#include "talus/narrow_phase.h"

namespace talus {

/// How penetration is removed. Every scheme keeps the speculative target
/// of the velocity rows (a gap may close this step, no further). A third
/// scheme, non-linear Gauss-Seidel position sweeps, was measured and
/// retired (docs/dynamics.md, "Retired options").
enum class PositionCorrection {
  /// The write-up's: a Baumgarte bias beta/h max(depth - slop, 0) in the
  /// velocity rows. The correction becomes velocity, so it adds kinetic
  /// energy and, with a small slop, rocks tall stacks.
  Baumgarte,
  /// The Baumgarte term moves to pseudo-velocities that move positions only
  /// and are thrown away (Bullet's split impulses). The depth is not updated
  /// during the sweeps.
  SplitImpulses,
};

/// How orientations and angular velocities advance over a step. Every
/// scheme applies torques as w += h I_world^-1 tau before the contact solve;
/// they differ in the torque-free part, Euler's equation
/// I dw/dt + w x (I w) = 0 (the gyroscopic term). An implicit gyroscopic
/// step (Catto 2015, Bullet's) was measured and retired: it loses 1 to 11%
/// of the angular momentum (docs/dynamics.md, "Retired options").
enum class RotationIntegrator {
  /// The write-up's: w constant in the world over the step, the
  /// orientation turned by the exact exponential of h w. No gyroscopic
  /// term: a tumbling asymmetric body keeps w, not L, constant (its L turns
  /// with the body) and never turns over about its intermediate axis.
  ConstantRate,
  /// The free rigid body splitting of Dullweber, Leimkuhler and McLachlan
  /// (J. Chem. Phys. 107, 1997): the solved w becomes the world angular
  /// momentum L = I_world w, held fixed over the drift, which is a
  /// symmetric sequence of exact rotations about the principal axes
  /// (x h/2, y h/2, z h, y h/2, x h/2), the body-frame momentum turned back
  /// by each. Each sub-rotation keeps L exactly, so a free body's L (vector
  /// and magnitude) is conserved to round-off; the scheme is symplectic and
  /// second order, so the energy error stays bounded, O((h |w|)^2), with no
  /// drift; the body turns over about its intermediate axis at the right
  /// period to O(h^2).
  MomentumSplitting,
  /// MomentumSplitting's drift made fourth order: the symmetric step S is
  /// composed as S(a h) S(b h) S(a h), a = 1 / (2 - 2^(1/3)), b = 1 - 2a
  /// (Yoshida, Phys. Lett. A 150, 1990). Still a sequence of exact rotations
  /// about the principal axes, so L is kept to round-off and the scheme is
  /// symplectic; the energy and attitude errors fall as O((h |w|)^4) instead
  /// of O((h |w|)^2), for 13 sub-rotations a step instead of 5.
  MomentumSplittingFourthOrder,
};

/// How centres of mass advance over a step.
enum class TranslationIntegrator {
  /// The write-up's symplectic Euler: x += h v(n+1), with the velocity after
  /// the contact solve. A free-falling body lags the parabola by g h t / 2
  /// (its energy falls by m g^2 h t / 2).
  SymplecticEuler,
  /// Exact for constant acceleration: a body the contact solver left
  /// untouched this step (no impulse changed its velocity) moves by
  /// h (v(n) + v(n+1)) / 2 = h v(n) + a h^2 / 2 (velocity Verlet with a
  /// constant force), so free flight follows the parabola to round-off. A
  /// body any contact impulse acted on moves by h v(n+1) as before, so the
  /// solver's velocity targets (speculative gaps, rest) keep their meaning.
  ExactConstantAcceleration,
};

/// When a bounce happens within a step (restitution e > 0, closing faster
/// than WorldSettings::restitutionThreshold).
enum class BounceTiming {
  /// The write-up's: the impact is taken at the step's boundary. The
  /// velocity row asks for -e times the closing speed after gravity, and the
  /// body then moves by h times that. A 1 m drop at 60 Hz hits up to one
  /// step early or late, so its apex errs by up to (1 + e^2) v h (11 cm for
  /// e = 0.7).
  StepBoundary,
  /// The impact is timed inside the step (dynamics/bounce_timing.h): from
  /// the point's gap, normal speed and normal acceleration at the step's
  /// start, the time t* in [-h, h] where it reaches the surface and its
  /// speed there. The velocity row asks for the normal speed the reflected
  /// flight has at the step's end, and a position row (a pseudo velocity,
  /// as split impulses) puts the point at that flight's end gap: the bounce
  /// is the exact one under constant acceleration, wherever in the step it
  /// falls. A point the last step carried through the surface (t* < 0) has
  /// that overshoot undone. Penetrations deeper than one step of approach
  /// (t* < -h) fall back to StepBoundary.
  TimeOfImpact,
};

/// In which order the contact rows are visited in a velocity sweep. Both
/// orders run Sequential Impulses: the same rows, clamps and block solve.
enum class ContactOrder {
  /// The write-up's order: one pair after another in pair order, one row
  /// at a time, scalar. The reference.
  PairByPair,
  /// The same rows, clamps and block solve, with the pairs coloured so that
  /// no two pairs of a colour share a body contacts can move, and each
  /// colour solved four pairs at a time in SIMD lanes (AVX2 when built with
  /// TALUS_SIMD=AVX2, else the same arithmetic lane by lane), its bundles
  /// splittable across threads with bit-identical results. Pairs that
  /// find no colour (or have more than four points) are solved one by one
  /// after the colours. A Gauss-Seidel sweep in another order: results
  /// differ from PairByPair by the order, not the method.
  ByColour,
};

/// How a pair's friction rows are solved in each sweep.
enum class FrictionSolve {
  /// The write-up's: two rows per point, one after another, each clamped to
  /// mu times its point's current normal impulse. Each row's impulse turns
  /// the body, which changes the slip the next point sees, so a sliding box
  /// yaws and its friction converges about a factor 2 per sweep (measured:
  /// a box stopping at 30 Hz ends 2.6e-5 m short with 5 sweeps, 8.6e-7 m
  /// with 10).
  PerPoint,
  /// A face contact (3 or 4 points, with the block solver on) first tries
  /// its normal rows and its friction as one block: the normals together with
  /// three friction patterns, the slip of the centre of pressure along t1
  /// and t2 and the spin about n, each shared among the points in
  /// proportion to their normal impulses. Accepted when every normal
  /// impulse pushes and every point's friction stays inside mu times its
  /// normal impulse (the pair sticks): the pair then stops in one sweep,
  /// where row by row each friction impulse tilts the body and the normals
  /// must undo it (a cube converges by 0.6 a sweep). Otherwise (sliding,
  /// lifting) the normal block and the per-point rows run as PerPoint. At a
  /// sticking solution the block asks for no change, so the answer is the
  /// per-point rows' fixed point, reached in fewer sweeps. Edge contacts
  /// keep the per-point rows (measured worse on tipping boxes). Needs
  /// blockSolver on and contactOrder = PairByPair: World::Create
  /// refuses it with either of the others, where it would do nothing.
  CoupledBlock,
  /// Three rows per pair instead of two per point: slip along t1 and t2 at
  /// the pair's centre of pressure (its points weighted by the normal
  /// impulses the step starts from), bounded together by a disc of radius
  /// mu times the pair's total normal impulse (the round Coulomb cone), and
  /// spin about n, bounded by mu times the sum of each point's normal
  /// impulse times its distance from the points' mean. A pair that slides
  /// and spins at once gets both bounds in full (per point they share one),
  /// so it is braked harder. Stored per point like PerPoint, so warm
  /// starting and StepStatistics read the same. Drops a light body under a
  /// heavy load (measured: 150:1 at 10 sweeps), which Adaptive catches.
  /// Needs contactOrder = PairByPair (World::Create refuses the coloured
  /// order, whose lanes hold per-point rows). docs/dynamics.md, "Friction
  /// per manifold".
  PerManifold,
  /// PerManifold's rows on every pair, except a pair whose load at the end
  /// of the last step exceeds 50 weights of its lighter moving body (m g h
  /// each), which is solved as under CoupledBlock: the cheaper rows where
  /// they converge, the exact stick solve where a light body carries a
  /// heavy load. Needs blockSolver on and contactOrder = PairByPair, as
  /// CoupledBlock. docs/dynamics.md, "Adaptive friction".
  Adaptive,
};

/// Which step solver advances the bodies (the pipeline after the narrow
/// phase; dynamics/soft_step_solver.h for the soft step's derivation).
enum class StepSolver {
  /// The write-up's: one velocity solve per step (Sequential Impulses with
  /// the options above: Baumgarte or split impulses, block solve, extra
  /// sweeps for new pairs), then one position update.
  SequentialImpulses,
  /// Box2D v3's and Box3D's soft step (Catto's Solver2D study): the step is
  /// cut into MethodSettings::softStep.substeps sub-steps, each integrating
  /// velocities, warm starting, solving the contacts once as soft springs
  /// (a stiffness and damping from a frequency and a damping ratio instead
  /// of Baumgarte's push), integrating positions and relaxing once without
  /// the spring's push; restitution after the last sub-step. Contact points
  /// come from the narrow phase once per step; each sub-step updates their
  /// separation from the bodies' motion since the step's start. The pairs
  /// are graph-coloured, so the result is the same bits for any thread
  /// count. Unused by it: velocityIterations, maxVelocityIterations,
  /// velocityTolerance, blockSolver, contactOrder, positionIterations,
  /// baumgarte, slop, positionCorrection, bounceTiming and
  /// frictionSolve.
  SoftStep,
};

/// The soft step's tunables (StepSolver::SoftStep). Validated at
/// World::Create and SetSettings.
struct SoftStepSettings {
  /// Sub-steps per step, [1, 1000]. Default 4, Box2D v3's and Box3D's
  /// default: the springs are stepped at 4 times the step rate.
  int substeps = 4;
  /// Most contact spring frequency, Hz, finite and > 0. The frequency used
  /// is min(contactHertz, 0.25 x sub-step rate) (Box2D v3: a spring stepped
  /// at fewer than four sub-steps per period is not resolved); a contact
  /// with an immovable body gets twice that (Box2D v3's static softness).
  /// Default 30, Box2D v3's: a resting contact sinks g / (2 pi f)^2 under its
  /// own weight (0.28 mm at 30 Hz, 0.07 mm at 60 Hz on the ground).
  double contactHertz = 30.0;
  /// Contact spring damping ratio, unitless, finite and >= 0. Default 10,
  /// Box2D v3's: strongly over-damped, so a penetration is removed without
  /// a rebound.
  double dampingRatio = 10.0;
  /// Fastest speed at which the spring pushes overlapping bodies apart,
  /// m/s, finite and > 0. Default 3, Box2D v3's contactSpeed: a deep
  /// overlap is undone over several steps instead of launching the bodies.
  double pushOutSpeed = 3.0;

  friend bool operator==(const SoftStepSettings&, const SoftStepSettings&) = default;
};
/// The method switches of a World (WorldSettings::methods). Every default is
/// the validated engine; each field names the write-up's choice beside it.
struct MethodSettings {
  /// Most velocity iterations, [1, 1000] (a value below velocityIterations
  /// means velocityIterations, the write-up's fixed count). In a step with
  /// new pairs (not touching last step, so no impulses to warm start from),
  /// sweeps past velocityIterations go on while the last one changed a row
  /// of a new pair by more than velocityTolerance. Default 200: a 10-box
  /// column whose contacts are all new needs ~150 sweeps in its first step
  /// not to sag by more than 1 mm; later steps are warm started and stop at
  /// velocityIterations.
  int maxVelocityIterations = 200;
  /// Convergence test of the extra sweeps, m/s, >= 0: the largest change a
  /// sweep made to a row of a new pair (its relative velocity). Default
  /// 1e-9: the residual of a new contact's first solve is never corrected
  /// afterwards (the rest sits inside the slop), so it stays as an offset of
  /// about velocityTolerance h per contact. 1e-3 left a 5e-5 rad tilt on a
  /// tall box and a 0.1 mm sag of a 5-box column at 1/30 s, where a direct
  /// solver is exact (docs/testbed-sweeps.md, "Run time against error").
  /// The extra sweeps run only in steps with new pairs.
  double velocityTolerance = 1e-9;
  /// Solve the normal rows of a pair with 2 to 4 points as one block (the
  /// least-norm solution of the pair's 4x4 system, Box2D v2.4's two-point
  /// block solver extended to four), falling back to row by row when that
  /// would make an impulse pull. Default on: row by row, the first corner
  /// solved takes more load than the others, the column tilts and a 10-box
  /// column sways by 8 cm; as a block it stays within 1e-7 m. Off is the
  /// write-up's one row at a time.
  bool blockSolver = true;
  /// Order and width of the velocity sweeps (see ContactOrder).
  /// Default PairByPair, the write-up's reference: on one thread
  /// the coloured solver measured no faster (the sweeps are bound by
  /// memory traffic, and packing the bundles costs Prepare time;
  /// docs/dynamics.md); ByColour is the order whose colours can be
  /// split across threads with bit-identical results.
  ContactOrder contactOrder = ContactOrder::PairByPair;
  /// Shock propagation: after the velocity sweeps, the pairs under a load
  /// that outweighs its support (or that the warm start has wrong by more
  /// than the support's weight) are swept again level by level from the
  /// immovable bodies up, each pair's lower body held (Guendelman et al.
  /// 2003), up to velocityIterations sweeps per level. Default on:
  /// Gauss-Seidel carries a heavy load onto light supports only after of the
  /// order of the mass ratio sweeps, and until then drives the supports into
  /// the ground; with the supports held a load's rows converge at a rate
  /// that does not depend on the ratio. Where no load outweighs its support
  /// nothing is swept. Off is the write-up's solver. docs/dynamics.md,
  /// "Shock propagation".
  bool shockPropagation = true;
  /// Scheme that removes penetration. Default Baumgarte, the write-up's.
  PositionCorrection positionCorrection = PositionCorrection::Baumgarte;
  /// When bounces happen (see BounceTiming). Default TimeOfImpact.
  BounceTiming bounceTiming = BounceTiming::TimeOfImpact;
  /// Carry accumulated impulses over from last step by feature id. Default
  /// on: stacks converge in a few iterations instead of hundreds.
  bool warmStarting = true;
  /// Rotation scheme (see RotationIntegrator). Default
  /// MomentumSplittingFourthOrder: the splitting keeps a free body's angular
  /// momentum to round-off where an implicit step loses 1 to 11% of it, and
  /// its fourth-order composition makes the energy error fall as
  /// O((h |w|)^4): on gazebo_boxes 36 times smaller than the second-order
  /// step's at 1/30 s and 140 times at 1/60 s, for about 25% more time on
  /// a one-body step (docs/dynamics.md, "Rotation"). ConstantRate is the write-up's (no
  /// gyroscopic term).
  RotationIntegrator rotation = RotationIntegrator::MomentumSplittingFourthOrder;
  /// Translation scheme (see TranslationIntegrator). Default
  /// ExactConstantAcceleration: free flight follows the parabola to
  /// round-off where SymplecticEuler lags it by g h t / 2, and the testbed
  /// measured it better or equal on every truth (docs/dynamics.md).
  /// SymplecticEuler is the write-up's.
  TranslationIntegrator translation = TranslationIntegrator::ExactConstantAcceleration;
  /// How friction rows are solved (see FrictionSolve). Default Adaptive:
  /// the manifold's rows with the coupled block on heavily loaded pairs,
  /// measured against CoupledBlock everywhere (the default before) on the
  /// whole suite and its time-step sweep, with the benchmark pyramids'
  /// steps cheaper (docs/dynamics.md, "Adaptive friction"). PerPoint is
  /// the write-up's, and the only one the coloured solver and the
  /// row-by-row normals (blockSolver off) have.
  FrictionSolve frictionSolve = FrictionSolve::Adaptive;
  /// Run WorldSettings::broadPhase in every world, however small. Default false: worlds
  /// of at most 128 active bodies take brute force whatever is selected,
  /// because it is measured faster there (docs/collision-broad-phase.md).
  /// Every structure yields the same pairs in the same order, so this
  /// changes speed and StepStatistics only (broadPhase.kindUsed says which
  /// structure ran); true is for figures and tests that must show the
  /// selected structure at work on a small scene.
  bool forceBroadPhase = false;
  /// SAT mode, manifold generator, SAT cache and speculative margin (see
  /// talus/narrow_phase.h); the margin must be finite and >= 0. The World's
  /// default margin is 0.02 m, not the narrow phase's 0: points that lift by
  /// round-off stay in the manifold (as speculative rows, dynamics/
  /// contact_solver.h), so resting contacts keep their warm start; measured,
  /// a resting box settles to 3e-7 m of its true height with it and to
  /// 2 mm (inside the slop) without.
  NarrowPhaseSettings narrowPhase = {.speculativeMargin = 0.02};
  /// Grow each pair's speculative margin (and each body's broad-phase
  /// sphere) by how far the bodies can move this step, h (|v| + |w| rho +
  /// g h), rho the farthest point's distance from the centre of mass, so a
  /// feature that can reach the other shape this step is in the manifold
  /// before it lands. Default on: a corner landing within the step is
  /// caught at the surface instead of sinking in and being pushed out (a
  /// tipping box at 1/30 s 0.18 -> 4.4e-4 tolerances, a hull landing 0.54 ->
  /// 4e-14), a fast box stops at a thin wall it tunnelled through above
  /// 7.3 m/s, and where the reach is below the fixed margin nothing changes
  /// (docs/dynamics.md, "Tunables"). Off is the write-up's fixed margin.
  bool speculativeMotion = true;
  /// Which step solver runs (see StepSolver). Default SequentialImpulses,
  /// the write-up's.
  StepSolver stepSolver = StepSolver::SequentialImpulses;
  /// The soft step's tunables (read only with StepSolver::SoftStep).
  SoftStepSettings softStep = {};
  /// Field by field (the testbed's rows compare whole settings).
  friend bool operator==(const MethodSettings&, const MethodSettings&) = default;
};

}  // namespace talus
