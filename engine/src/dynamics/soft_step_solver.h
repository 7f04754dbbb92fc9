// SoftStepSolver: the soft step (MethodSettings::stepSolver =
// StepSolver::SoftStep), after Box2D v3 and Box3D (Catto's Solver2D study,
// 2024: of the solvers it compared, the most robust per unit of cost). Our
// own code; the rows and notation are the Sequential Impulses solver's
// (dynamics/contact_row_set.h: n from B to A, rA = p - cA, rB = p - cB,
// dv = (vA + wA x rA) - (vB + wB x rB), J = [n, rA x n, -n, -rB x n]).
//
// The step (h = dt / substeps):
//   Prepare: rows from this step's contacts (the narrow phase ran once, at
//     the step's start): arms, Jacobians and effective masses fixed for the
//     step, accumulated impulses loaded from last step (warm start).
//   Each of `substeps` sub-steps:
//     1. integrate velocities: v += h (g + F / m), w += h I^-1 tau;
//     2. warm start: apply each row's accumulated impulse;
//     3. solve once with the soft bias (below);
//     4. integrate positions: the world's schemes (dynamics/integrator.h);
//     5. relax: solve once more, rigid, without the bias, so the spring's
//        push does not stay in the velocities as kinetic energy.
//   Then restitution, once (below), and the impulses stored back.
//
// Separation in a sub-step. The points are not recomputed by the narrow
// phase: each point keeps its arms rA, rB and depth d0 from the step's
// start, and its gap (> 0 apart) now is
//   C = -d0 + n . ((cA - cA0) - (cB - cB0) + (qA lA - rA) - (qB lB - rB)),
// with cA0 the centre at the step's start, lA = qA0^-1 rA the arm in A's
// axes and qA lA where the rotations since then have carried it (current
// minus initial positions, so no large coordinate cancels). The normal is
// the step's; a pair that turns far within one step is caught by the next
// step's narrow phase.
//
// Soft constraint (Catto, "Soft constraints", GDC 2011; Box2D v3's
// b2MakeSoft). A row of effective mass m and error C acts as a spring of
// stiffness k = m w^2 and damper c = 2 m z w (w = 2 pi f, f the frequency,
// z the damping ratio) on C. Implicit Euler over the sub-step, with v1 the
// row's velocity before the impulse lambda and v2 = v1 + lambda / m after:
//   m (v2 - v1) = -h (k (C + h v2) + c v2)
//   =>  lambda = -m / (1 + a2) (a2 v1 + h w^2 C),   a1 = 2 z + h w,
//                                                   a2 = h w a1 = h c/m + h^2 k/m
//             = -m massScale (v1 + biasRate C),
//   biasRate = h w^2 / a2 = w / a1,   massScale = a2 / (1 + a2).
// The iterative solve sees v1 with the accumulated impulse lambda_acc
// already applied (v1 = v_free + lambda_acc / m); the spring's total is
// -m massScale (v_free + biasRate C), so the increment is
//   dlambda = -m massScale (v1 + biasRate C) - impulseScale lambda_acc,
//   impulseScale = 1 - massScale = 1 / (1 + a2),
// then clamped so that lambda_acc stays >= 0 (contacts push). A rigid row
// is massScale 1, impulseScale 0, biasRate 0. At rest under a load F the
// spring holds C = -F / k: a box on four corners (each corner's effective
// mass m/4 for a cube, load m g / 4) sinks g / w^2.
//   Per point:  C > 0 (a gap, speculative): rigid, bias C / h (the gap may
//                 close this sub-step, no further);
//               C <= 0, solve: soft, bias max(biasRate C, -pushOutSpeed);
//               C <= 0, relax: rigid, bias 0.
//   Frequency: f = min(contactHertz, substep rate / 4) (a spring stepped
//   fewer than four times a period is not resolved), 2 f against an
//   immovable body (Box2D v3's static softness: the ground holds twice as
//   stiff, the load on it is the largest). This replaces Baumgarte's push,
//   the slop and the extra sweeps on new contacts: a new contact is a stiff
//   damped spring that converges over the sub-steps, not a rigid row that
//   needs many sweeps in one.
//
// Block (a pair of 2 to 4 points, every point touching, C <= 0): the
// pair's normal rows solved together, the vector form of the row above,
//   dlambda = -massScale K+ (v + bias) - impulseScale lambda_acc,
// K = J M^-1 J^T (4x4, rank 3 for four coplanar points, so its
// pseudo-inverse K+, from an eigen decomposition at Prepare, the least-norm
// split), accepted when every impulse stays >= 0, else point by point.
// Why: point by point, the first corner solved takes more than its share;
// a light body pressed by a heavy one (its impulses hundreds of times its
// own weight) was left rocking by that error every sub-step (a 125 kg cube
// under a 100:1 plank never came to rest: 0.01-0.09 rad/s after 30 s), and
// a column of new contacts swayed 2 mm. At rest the block's spring holds
// C = -K lambda / (h w^2): for a load shared evenly by a cube's corners the
// same g / w^2 as row by row.
//
// Friction: two rows per point along t1 (the sliding direction when there
// is one) and t2 = n x t1, rigid, each clamped to mu times the point's
// current normal impulse, solved after the pair's normal rows.
//
// Restitution (Box2D v3): after the sub-steps, a point with e > 0 that
// closed faster than restitutionThreshold at the step's start (approach
// speed u0 = n . dv < -threshold) and that pushed during the step gets one
// rigid row with target -e u0, its accumulated impulse still >= 0.
//
// Order and threads. The pairs are graph-coloured (dynamics/
// constraint_colouring.h; the two bodies of a pair, immovable ones not
// counting): pairs of one colour share no body the rows may write, so a
// colour's pairs may run in any order, at once, with the same bits. A pass
// (warm start, solve, relax, restitution) runs the colours in order, each
// colour's pairs in pair order, then the overflow pairs one by one. The
// whole step, integration included, is one chain of phases on the world's
// threads (jobs/job_pool.h): the results are bit-identical for any thread
// count. The rows read and write the bodies' own velocities (BodySim);
// only rows of a body they may move write it.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "dynamics/body_sim.h"
#include "dynamics/constraint_colouring.h"
#include "dynamics/contact.h"
#include "dynamics/soft_contact_rows.h"
#include "jobs/job_pool.h"
#include "talus/step_statistics.h"
#include "talus/world_settings.h"

namespace talus {

/// Why the soft step's settings of `settings` are invalid (names the field
/// and its range), or an empty string when they are valid. Checked whatever
/// stepSolver says, so a world switched to the soft step later never holds
/// bad values.
std::string ValidateSoftStepSettings(const WorldSettings& settings);

class SoftStepSolver {
 public:
  /// How the step's phases are spread over threads (unset: in order on the
  /// caller). Results do not depend on it.
  void SetPhaseRunner(PhaseRunner runner) { m_runner = std::move(runner); }

  /// Builds the rows of `contacts` (this step's, impulses carried over from
  /// last step when warm starting) for a step of `dt` seconds and colours
  /// the pairs. Adds its counts to `stats`.
  void Prepare(std::span<const BodySim> bodies, std::span<const Contact> contacts,
               const WorldSettings& settings, double dt, StepStatistics& stats);
  /// Runs the sub-steps, integration included, then restitution; moves
  /// `bodies` (the array handed to Prepare) to the step's end and clears
  /// their accumulated forces. Returns the dynamic bodies integrated.
  int Step(std::span<BodySim> bodies, const WorldSettings& settings, double dt);
  /// Writes the accumulated impulses back into `contacts` for next step's
  /// warm start, as impulses over the whole step (the sub-step's times the
  /// sub-step count: what Sequential Impulses stores too).
  void StoreImpulses(std::span<Contact> contacts) const;

  [[nodiscard]] int PairCount() const { return static_cast<int>(m_pairs.size()); }
  /// Colours in use and the pairs of the overflow colour, of the last Prepare.
  [[nodiscard]] int ColourCount() const { return static_cast<int>(m_colourStart.size()) - 1; }
  [[nodiscard]] int OverflowCount() const { return static_cast<int>(m_overflow.size()); }

 private:
  enum class Pass : std::uint8_t { WarmStart, Solve, Relax, Restitution };
  /// One phase of the step's chain.
  struct PhaseJob {
    enum class Kind : std::uint8_t { IntegrateVelocities, IntegratePositions, Colour, Overflow, ClearForces };
    Kind kind = Kind::Colour;
    Pass pass = Pass::Solve;
    int colour = 0;
  };

  void PreparePair(std::span<const BodySim> bodies, const Contact& contact, const WorldSettings& settings,
                   SoftPair& pair);
  void RunPass(std::span<BodySim> bodies, Pass pass, const SoftPair& pair);
  void WarmStartPair(std::span<BodySim> bodies, const SoftPair& pair);
  void SolvePair(std::span<BodySim> bodies, const SoftPair& pair, bool useBias);
  /// The block of `pair`'s normal rows with the gaps `gaps`: true when
  /// accepted (impulses written and applied to `a`, `b`).
  bool SolveBlock(const SoftPair& pair, const double* gaps, bool useBias, Vec3& va, Vec3& wa, Vec3& vb,
                  Vec3& wb);
  void PrepareBlock(const SoftPair& pair);
  void RestitutionPair(std::span<BodySim> bodies, const SoftPair& pair);
  void Colour(int bodyCount);
  void AddPass(Pass pass);

  std::vector<SoftPair> m_pairs;
  std::vector<SoftPoint> m_points;
  std::vector<Eigen::Matrix4d> m_blockInverses;  ///< K+ of the pairs with a block
  std::vector<int> m_colourPairs;                ///< pair indices, colour by colour, pair order within
  std::vector<int> m_colourStart;  ///< colour c's pairs: m_colourPairs[m_colourStart[c] .. [c + 1])
  std::vector<int> m_overflow;     ///< pairs solved one by one after the colours, in pair order
  std::vector<PhaseJob> m_jobs;    ///< the step's chain (scratch)
  std::vector<JobPhase> m_phases;  ///< its loops (scratch)
  // Colouring scratch, kept between steps.
  std::vector<ColourInput> m_inputs;
  std::vector<int> m_colourOf;
  std::vector<std::uint32_t> m_used;
  PhaseRunner m_runner;
  double m_h = 0.0;  ///< s, the sub-step
  double m_pushOutSpeed = 0.0;
  double m_restitutionThreshold = 0.0;
  int m_substeps = 1;
};

}  // namespace talus
