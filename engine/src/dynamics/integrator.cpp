// Symplectic Euler with an optional implicit gyroscopic term; see
// dynamics/integrator.h for the scheme and its sources.
#include "dynamics/integrator.h"

#include <cmath>

namespace talus {
namespace {

Mat3 Skew(const Vec3& a) {
  Mat3 s;
  s << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return s;
}

}  // namespace

Vec3 GyroscopicStep(const BodySim& body, double h) {
  // Work in body axes where the inertia is constant.
  const Quat& q = body.orientation;
  const Vec3 w1 = q.conjugate() * body.angularVelocity;
  const Mat3& inertia = body.inertiaLocal;
  const Vec3 iw = inertia * w1;
  const Vec3 residual = h * w1.cross(iw);
  const Mat3 jacobian = inertia + h * (Skew(w1) * inertia - Skew(iw));
  const Vec3 w2 = w1 - jacobian.inverse() * residual;
  return q * w2;
}

int IntegrateVelocities(std::span<BodySim> bodies, const Vec3& gravity, bool gyroscopic, double h) {
  int integrated = 0;
  for (BodySim& body : bodies) {
    if (body.type != BodyType::Dynamic || !body.awake) {
      body.force.setZero();
      body.torque.setZero();
      continue;
    }
    // Equation (1) of the write-up, with gravity as an acceleration so that
    // every mass falls alike.
    body.linearVelocity += h * (gravity + body.invMass * body.force);
    if (gyroscopic) body.angularVelocity = GyroscopicStep(body, h);
    body.angularVelocity += h * (body.invInertiaWorld * body.torque);
    body.force.setZero();
    body.torque.setZero();
    ++integrated;
  }
  return integrated;
}

void IntegratePositions(std::span<BodySim> bodies, double h, bool usePseudoVelocities) {
  for (BodySim& body : bodies) {
    if (!body.IsMoving()) continue;
    Vec3 v = body.linearVelocity;
    Vec3 w = body.angularVelocity;
    if (usePseudoVelocities) {
      v += body.pseudoLinear;
      w += body.pseudoAngular;
      body.pseudoLinear.setZero();
      body.pseudoAngular.setZero();
    }
    // Equation (2): the new velocity moves the body.
    body.center += h * v;
    const double angle = w.norm() * h;
    if (angle > 0.0) {
      // exp of a constant rotation rate over the step: a rotation by |w| h
      // about w, exact and unit length by construction; the normalise only
      // removes accumulated round-off.
      const Quat dq(Eigen::AngleAxisd(angle, w / w.norm()));
      body.orientation = (dq * body.orientation).normalized();
      body.UpdateWorldInertia();
    }
  }
}

}  // namespace talus
