// The soft step's per-step constraint rows (StepSolver::SoftStep;
// dynamics/soft_step_solver.h for the step and the derivation of the
// softness): one SoftPair per touching pair, one SoftPoint per contact
// point, and the Softness coefficients a row's spring is solved with.
//
// Shaped for more constraint types. A SoftPair is "two bodies and their
// rows": body indices, each body's inverse mass and whether the rows may
// write it, and a run of rows, each a RowJacobian (the angular parts and
// their images under the inverse inertia, dynamics/contact_rows.h), an
// effective mass, an accumulated impulse and the Softness it is solved
// with. A ball, hinge or fixed joint is the same: two bodies, three to six
// rows built from anchors in the bodies' frames (kept like a point's
// localAnchorA/B here, so its error is re-measured each sub-step), bilateral
// instead of clamped at zero, its own Softness (a joint frequency). It
// colours by the same two-body ColourInput (dynamics/constraint_colouring.h)
// and is solved in the same colour phases of the sub-step loop, beside the
// contact pairs, with the same (bodies, useBias) solve signature.
#pragma once

#include "dynamics/contact_rows.h"
#include "talus/math.h"

namespace talus {

/// The coefficients of a soft row over one sub-step (derivation in
/// dynamics/soft_step_solver.h). The rigid row is {0, 1, 0}.
struct Softness {
  double biasRate = 0.0;      ///< 1/s: the spring's push per metre of error, as a velocity
  double massScale = 1.0;     ///< unitless in [0, 1]: the share of the effective mass the row applies
  double impulseScale = 0.0;  ///< unitless in [0, 1]: the share of the accumulated impulse it gives back
};

/// Softness of a spring of `hertz` (> 0) and `dampingRatio` (>= 0) solved
/// over a sub-step of `h` seconds (> 0).
Softness MakeSoftness(double hertz, double dampingRatio, double h);

/// One contact point of a soft pair.
struct SoftPoint {
  /// rA = p - cA and rB = p - cB at the step's start (p the manifold
  /// point, world axes, metres): the rows' fixed lever arms.
  Vec3 armA = Vec3::Zero();
  Vec3 armB = Vec3::Zero();
  /// The same arms in A's and B's body axes: turned by a body's current
  /// orientation, where the point has moved with it since the step's start.
  Vec3 localAnchorA = Vec3::Zero();
  Vec3 localAnchorB = Vec3::Zero();
  RowJacobian normal;
  RowJacobian tangent[2];
  double normalMass = 0.0;                ///< kg, effective mass along n
  double tangentMass[2] = {0.0, 0.0};     ///< kg, along t1 and t2
  double depth = 0.0;                     ///< m, the narrow phase's (> 0 overlapping, < 0 a gap)
  double normalImpulse = 0.0;             ///< N s, accumulated over the current sub-step
  double tangentImpulse[2] = {0.0, 0.0};  ///< N s
  double maxNormalImpulse = 0.0;          ///< N s, the largest of the step (restitution: did it touch)
  double approachSpeed = 0.0;             ///< m/s, n . dv at the step's start (restitution)
};

/// One touching pair of a soft step.
struct SoftPair {
  int bodyA = -1, bodyB = -1;  ///< body indices (into the world's BodySims)
  int firstPoint = 0, pointCount = 0;
  int contact = -1;            ///< index into the contacts handed to Prepare
  Vec3 normal = Vec3::Zero();  ///< from B towards A, fixed over the step
  Vec3 tangent[2] = {Vec3::Zero(), Vec3::Zero()};
  Vec3 startCenterA = Vec3::Zero();  ///< centres of mass at the step's start, metres
  Vec3 startCenterB = Vec3::Zero();
  double invMassA = 0.0, invMassB = 0.0;  ///< 1/kg; 0 for a body contacts cannot move
  bool movesA = false, movesB = false;    ///< whether the rows write the body's velocities
  double friction = 0.0;
  double restitution = 0.0;
  Softness softness;  ///< the spring of the pair's normal rows
  int block = -1;     ///< index of the pair's K+ (2-4 points), -1 when solved point by point
};

}  // namespace talus
