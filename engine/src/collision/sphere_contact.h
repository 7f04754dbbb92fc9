// Exact contacts of a sphere (always shape A here) with a sphere, a box or
// a convex hull (shape B). The dispatcher swaps roles for hull-sphere.
//
// Each routine finds the closest features exactly: centre to centre, the
// centre clamped to the box, or the closest point on the hull's faces
// visible from the centre. A centre inside the box or hull is pushed out
// through the face it is nearest (the deepest face). Every routine returns
// at most one point, positioned midway between the two surfaces, with the
// normal from B towards A. A pair that does not touch still gets its
// normal and depth (minus the exact gap) written, with no points.
#pragma once

#include "collision/contact_manifold.h"
#include "talus/shape.h"
#include "talus/transform.h"

namespace talus {

/// Below this centre-to-feature distance (metres) the direction between
/// them is meaningless; the routines then use a face normal, or +Y for two
/// concentric spheres. 1e-12 m: far below any modelled size.
inline constexpr double kSphereDirectionEpsilon = 1e-12;

/// Sphere `a` against sphere `b`. Fills `out` and returns true when they
/// overlap or are within `margin` (metres, >= 0).
bool CollideSphereSphere(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                         double margin, ContactManifold* out);

/// Sphere `a` against box `b` (closed form).
bool CollideSphereBox(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                      double margin, ContactManifold* out);

/// Sphere `a` against convex hull `b` (any polyhedron shape).
bool CollideSphereHull(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                       double margin, ContactManifold* out);

}  // namespace talus
