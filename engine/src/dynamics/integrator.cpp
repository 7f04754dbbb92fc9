// Symplectic Euler with a choice of rotation scheme (constant rate, free
// rigid body splitting of second or fourth order) and of translation scheme; see
// dynamics/integrator.h for the schemes and their sources.
#include "dynamics/integrator.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

namespace talus {
namespace {

// q turned by the exact exponential of a constant rate w over h (world
// axes): a rotation by |w| h about w, unit by construction; the normalise
// only removes accumulated round-off.
Quat TurnAtConstantRate(const Quat& q, const Vec3& w, double h) {
  const double rate = w.norm();
  if (!(rate > 0.0)) return q;
  const Quat dq(Eigen::AngleAxisd(rate * h, w / rate));
  return (dq * q).normalized();
}

// The exact flow of H_i = pi_i^2 / (2 I_i) over t: the body turns about its
// principal axis i by t pi_i / I_i (turn <- turn R_i) and pi, seen from the
// body, turns back by the same angle, so R pi stays the same.
void FlowAboutPrincipalAxis(int axis, double t, const Vec3& moments, Vec3& pi, Quat& turn) {
  const double angle = t * pi[axis] / moments[axis];
  const int j = (axis + 1) % 3;
  const int k = (axis + 2) % 3;
  // One sine and one cosine of the half angle serve the quaternion and,
  // by the double-angle formulas, the momentum's turn.
  const double halfCos = std::cos(0.5 * angle);
  const double halfSin = std::sin(0.5 * angle);
  const double c = halfCos * halfCos - halfSin * halfSin;
  const double s = 2.0 * halfSin * halfCos;
  const double pj = pi[j];
  const double pk = pi[k];
  pi[j] = c * pj + s * pk;
  pi[k] = c * pk - s * pj;
  Quat half(halfCos, 0.0, 0.0, 0.0);
  half.vec()[axis] = halfSin;
  turn = turn * half;
}

// Yoshida's triple jump (Phys. Lett. A 150, 1990): the symmetric second
// order step S(h) composed as S(a h) S(b h) S(a h) with 2a + b = 1 and
// 2a^3 + b^3 = 0, i.e. a = 1 / (2 - 2^(1/3)), b = 1 - 2a (negative: the
// middle step runs backwards), cancels the h^3 term of the local error, so
// the composition is fourth order and still symmetric and symplectic. Each
// S is the Strang sequence x a/2, y a/2, z a, y a/2, x a/2; the x flows
// where two S meet are about the same axis, so they commute and merge into
// one: 13 exact sub-rotations instead of 15.
constexpr double kTripleJumpOuter = 1.3512071919596578;   // 1 / (2 - 2^(1/3))
constexpr double kTripleJumpInner = -1.7024143839193155;  // 1 - 2 kTripleJumpOuter
struct AxisFlow {
  int axis;
  double fraction;  // of the step
};
constexpr AxisFlow kTripleJumpFlows[] = {
    {0, 0.5 * kTripleJumpOuter},
    {1, 0.5 * kTripleJumpOuter},
    {2, kTripleJumpOuter},
    {1, 0.5 * kTripleJumpOuter},
    {0, 0.5 * (kTripleJumpOuter + kTripleJumpInner)},
    {1, 0.5 * kTripleJumpInner},
    {2, kTripleJumpInner},
    {1, 0.5 * kTripleJumpInner},
    {0, 0.5 * (kTripleJumpInner + kTripleJumpOuter)},
    {1, 0.5 * kTripleJumpOuter},
    {2, kTripleJumpOuter},
    {1, 0.5 * kTripleJumpOuter},
    {0, 0.5 * kTripleJumpOuter},
};

}  // namespace

PrincipalAxes ComputePrincipalAxes(const Mat3& inertia) {
  PrincipalAxes axes;
  const bool diagonal = inertia(0, 1) == 0.0 && inertia(0, 2) == 0.0 && inertia(1, 2) == 0.0 &&
                        inertia(1, 0) == 0.0 && inertia(2, 0) == 0.0 && inertia(2, 1) == 0.0;
  if (diagonal) {
    axes.moments = inertia.diagonal();
    return axes;
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(inertia);
  Mat3 frame = solver.eigenvectors();
  // Eigenvectors come with either sign: make the frame a proper rotation.
  if (frame.determinant() < 0.0) frame.col(2) = -frame.col(2);
  axes.frame = Quat(frame).normalized();
  axes.moments = solver.eigenvalues();
  return axes;
}

FreeRotation SplitFreeRotation(const Quat& orientation, const PrincipalAxes& principal, const Vec3& momentum,
                               double h, SplittingOrder order) {
  const Vec3& moments = principal.moments;
  if (moments[0] == moments[1] && moments[1] == moments[2]) {
    // Equal moments (a sphere, a cube): I w x w = 0, so w = L / I stays
    // constant and the exact flow is one turn at that rate. The splitting
    // would only approximate it (its sub-flows do not commute even here)
    // at 5 or 13 sines and cosines; with L = 0 nothing turns at all.
    FreeRotation out;
    out.angularVelocity = momentum / moments[0];
    out.orientation = TurnAtConstantRate(orientation, out.angularVelocity, h);
    return out;
  }
  if (momentum.isZero(0.0)) return {orientation, Vec3::Zero()};  // no flow to follow
  // Principal axes to world, and the momentum seen from them.
  const Quat start = orientation * principal.frame;
  Vec3 pi = start.conjugate() * momentum;
  const double magnitude = pi.norm();
  Quat turn = Quat::Identity();
  if (order == SplittingOrder::Fourth) {
    for (const auto& [axis, fraction] : kTripleJumpFlows) {
      FlowAboutPrincipalAxis(axis, fraction * h, moments, pi, turn);
    }
  } else {
    FlowAboutPrincipalAxis(0, 0.5 * h, moments, pi, turn);
    FlowAboutPrincipalAxis(1, 0.5 * h, moments, pi, turn);
    FlowAboutPrincipalAxis(2, h, moments, pi, turn);
    FlowAboutPrincipalAxis(1, 0.5 * h, moments, pi, turn);
    FlowAboutPrincipalAxis(0, 0.5 * h, moments, pi, turn);
  }
  // Every sub-flow keeps |pi| exactly; the rounded cos and sin of angles
  // that repeat step after step do not (c^2 + s^2 - 1 ~ 1e-16 with the same
  // sign each step: 2.6e-12 of |L| in 1e4 steps, measured). Putting |pi|
  // back is a projection onto the flow's own invariant, not a correction of
  // the method.
  if (const double now = pi.norm(); now > 0.0) pi *= magnitude / now;
  const Quat end = (start * turn).normalized();
  FreeRotation out;
  out.orientation = (end * principal.frame.conjugate()).normalized();
  out.angularVelocity = end * pi.cwiseQuotient(moments);
  return out;
}

int IntegrateVelocities(std::span<BodySim> bodies, const Vec3& gravity, double h) {
  int integrated = 0;
  for (BodySim& body : bodies) {
    if (body.type != BodyType::Dynamic || !body.awake) {
      body.force.setZero();
      body.torque.setZero();
      continue;
    }
    // Equation (1) of the write-up, with gravity as an acceleration so that
    // every mass falls alike.
    body.startLinearVelocity = body.linearVelocity;
    body.linearVelocity += h * (gravity + body.invMass * body.force);
    body.freeLinearVelocity = body.linearVelocity;
    body.angularVelocity += h * (body.invInertiaWorld * body.torque);
    body.force.setZero();
    body.torque.setZero();
    ++integrated;
  }
  return integrated;
}

void IntegratePositions(std::span<BodySim> bodies, double h, bool usePseudoVelocities,
                        RotationIntegrator rotation, TranslationIntegrator translation) {
  for (BodySim& body : bodies) {
    if (!body.IsMoving()) continue;
    const bool dynamic = body.type == BodyType::Dynamic;
    // Equation (2): the new velocity moves the body; for a body no impulse
    // touched, the exact scheme uses the mean of the old and new velocity.
    const bool free = dynamic && translation == TranslationIntegrator::ExactConstantAcceleration &&
                      body.linearVelocity == body.freeLinearVelocity;
    Vec3 v = free ? Vec3(0.5 * (body.startLinearVelocity + body.linearVelocity)) : body.linearVelocity;
    Vec3 pseudoAngular = Vec3::Zero();
    if (usePseudoVelocities) {
      v += body.pseudoLinear;
      pseudoAngular = body.pseudoAngular;
      body.pseudoLinear.setZero();
      body.pseudoAngular.setZero();
    }
    body.center += h * v;
    Quat q = body.orientation;
    if (dynamic && (rotation == RotationIntegrator::MomentumSplitting ||
                    rotation == RotationIntegrator::MomentumSplittingFourthOrder)) {
      // L of the solved w at the attitude it was solved at (the last drift's
      // own L when nothing changed w since), then the drift that keeps it;
      // the pseudo-velocity (a position correction, not momentum) turns the
      // result at its constant rate.
      const Vec3 momentum = body.angularVelocity == body.keptAngularVelocity
                                ? body.keptAngularMomentum
                                : Vec3(q * (body.inertiaLocal * (q.conjugate() * body.angularVelocity)));
      const FreeRotation drift = SplitFreeRotation(
          q, {body.principalFrame, body.principalInertia}, momentum, h,
          rotation == RotationIntegrator::MomentumSplittingFourthOrder ? SplittingOrder::Fourth
                                                                       : SplittingOrder::Second);
      body.keptAngularMomentum = momentum;
      body.keptAngularVelocity = drift.angularVelocity;
      q = TurnAtConstantRate(drift.orientation, pseudoAngular, h);
      body.angularVelocity = drift.angularVelocity;
    } else {
      q = TurnAtConstantRate(q, body.angularVelocity + pseudoAngular, h);
      body.keptAngularVelocity.setConstant(std::numeric_limits<double>::quiet_NaN());
    }
    if (q.coeffs() != body.orientation.coeffs()) {
      body.orientation = q;
      body.UpdateWorldInertia();
    }
  }
}

}  // namespace talus
