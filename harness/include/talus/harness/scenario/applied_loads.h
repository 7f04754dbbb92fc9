// When a scenario's loads and impulses act, in every backend's time steps,
// and what they are in world axes: the one schedule every backend follows,
// so each engine receives the same forces and differs only in what it does
// with them (docs/scenarios.md, "Loads, impulses and kinematic bodies").
//
// Header-only on purpose: the single-precision Bullet module links no
// harness code (bullet_world.h), and these are a few lines of arithmetic.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include "talus/harness/scenario/scenario.h"

namespace talus::harness {

/// The share of `load` acting during the step [t, t + h): the overlap of the
/// step with [start, end), divided by h (0 outside, 1 inside, a fraction on
/// a window's edge). A backend applies share x force for the whole step, so
/// the impulse delivered over the run is force x (end - start) exactly, at
/// any time step.
inline double AppliedLoadShare(const AppliedLoad& load, double t, double h) {
  const double overlap = std::min(t + h, load.end) - std::max(t, load.start);
  return overlap > 0.0 ? std::min(overlap / h, 1.0) : 0.0;
}

/// Whether `impulse` is given at the start of step `step` (numbered from 0)
/// of length h: the step whose start is nearest its time.
inline bool AppliedImpulseAtStep(const AppliedImpulse& impulse, long long step, double h) {
  return std::llround(impulse.time / h) == step;
}

/// A load for one step in world axes.
struct WorldLoad {
  Vec3 force = Vec3::Zero();   ///< N
  Vec3 torque = Vec3::Zero();  ///< N m, the file's torque only (not the force's moment)
  /// Where the force acts, metres, world; none: the centre of mass.
  std::optional<Vec3> point = std::nullopt;
};

/// `load` scaled by `share`, in world axes, for a body whose frame is at
/// `origin` with `orientation` at the step's start (the engine's own pose).
inline WorldLoad ToWorldLoad(const AppliedLoad& load, double share, const Vec3& origin,
                             const Quat& orientation) {
  const Mat3 rotation = orientation.toRotationMatrix();
  const bool body = load.frame == LoadFrame::Body;
  WorldLoad out;
  out.force = share * (body ? Vec3(rotation * load.force) : load.force);
  out.torque = share * (body ? Vec3(rotation * load.torque) : load.torque);
  if (load.point) out.point = Vec3(origin + rotation * *load.point);
  return out;
}

/// The world point of an impulse's body-frame point, for a body frame at
/// `origin` with `orientation`; none when the impulse acts at the centre.
inline std::optional<Vec3> ImpulseWorldPoint(const AppliedImpulse& impulse, const Vec3& origin,
                                             const Quat& orientation) {
  if (!impulse.point) return std::nullopt;
  return Vec3(origin + orientation.toRotationMatrix() * *impulse.point);
}

/// A kinematic body's frame at time t: the origin at p0 + v t, the
/// orientation turned by the angle |w| t about the world axis w (both
/// constant), so the body turns about its origin. Every backend places (or
/// moves) its kinematic bodies along this.
struct KinematicPose {
  Vec3 origin = Vec3::Zero();
  Quat orientation = Quat::Identity();
};
inline KinematicPose KinematicPoseAt(const BodySpec& body, double t) {
  KinematicPose pose;
  pose.origin = body.position + t * body.linearVelocity;
  const double angle = body.angularVelocity.norm() * t;
  pose.orientation =
      angle > 0.0 ? Quat(Eigen::AngleAxisd(angle, body.angularVelocity.normalized())) * body.orientation
                  : body.orientation;
  pose.orientation.normalize();
  return pose;
}

}  // namespace talus::harness
