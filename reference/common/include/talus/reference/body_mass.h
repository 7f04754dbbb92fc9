// Mass properties of scenario bodies, computed once here so that every peer
// gets identical mass, centre of mass and inertia (engines' own estimates
// differ: Bullet's btConvexHullShape uses its bounding box).
//
// Boxes and spheres are analytic; hulls integrate over the triangulated
// boundary (each triangle with the origin forms a signed tetrahedron; sums of
// tetrahedron volumes, first and second moments are exact for the solid;
// Blow and Binstock, "How to find the inertia tensor (or other mass
// properties) of a 3D solid body represented by a triangle mesh", 2004).
#pragma once

#include "talus/harness/scenario/scenario.h"
#include "talus/math.h"
#include "talus/reference/point_hull.h"
#include "talus/result.h"

namespace talus::reference {

/// A body's mass properties in its scenario frame, plus the principal frame
/// engines that want a diagonal inertia (Bullet, ODE's dMass is full but its
/// body frame must be the centre of mass) place their bodies in.
struct BodyMass {
  double volume = 0.0;                        ///< m^3
  double mass = 0.0;                          ///< kg (0 for static bodies)
  Vec3 centroid = Vec3::Zero();               ///< centre of mass in the body frame, metres
  Mat3 inertia = Mat3::Zero();                ///< about the centroid, body axes, kg m^2
  Quat principalRotation = Quat::Identity();  ///< body axes -> principal axes: inertia = R diag R^T
  Vec3 principalInertia = Vec3::Zero();       ///< diagonal in the principal frame, kg m^2
};

/// Solid properties per unit density of a closed outward triangle mesh.
struct SolidMoments {
  double volume = 0.0;           ///< m^3
  Vec3 centroid = Vec3::Zero();  ///< metres
  Mat3 inertia = Mat3::Zero();   ///< about the centroid at density 1, m^5
};
SolidMoments ComputeSolidMoments(const PointHull& hull);

/// Mass properties of `body` (its mass, or density times volume). A hull
/// shape is triangulated with ComputePointHull; its error is passed on.
Result<BodyMass> ComputeBodyMass(const harness::BodySpec& body);

}  // namespace talus::reference
