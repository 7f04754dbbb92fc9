// Mass properties of a uniform-density convex polyhedron, computed exactly
// (by divergence-theorem integration over the faces), not from a
// triangulated approximation.
#pragma once

#include "talus/hull.h"
#include "talus/math.h"
#include "talus/result.h"

namespace talus {

/// Mass, centre of mass and inertia of a solid body.
struct MassProperties {
  double volume = 0.0;               ///< m^3
  double mass = 0.0;                 ///< kg
  Vec3 centerOfMass = Vec3::Zero();  ///< metres, in the hull's own frame
  Mat3 inertia = Mat3::Zero();       ///< kg m^2, about the centre of mass, hull-frame axes
};

/// Exact mass properties of `hull` filled with uniform `density` (kg/m^3,
/// finite and > 0; anything else is refused with an error).
Result<MassProperties> ComputeMassProperties(const Hull& hull, double density);

}  // namespace talus
