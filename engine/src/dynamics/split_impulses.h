// Split impulses (MethodSettings::positionCorrection = SplitImpulses) and
// the timed bounces' position rows: pseudo-velocity rows solved after the
// velocities, whose result only the position update adds.
//
// Position correction. Baumgarte (the write-up's) is the bias in the
// velocity target (dynamics/contact_row_set.h). Split impulses move it to
// pseudo-velocities: the same normal row on (pv, pw) with target beta/h
// max(depth - slop, 0), accumulated impulse clamped to [0, inf), so
// position correction cannot add kinetic energy. A timed bounce's row
// (PointCold::timedBounce) is an equality onto the reflected flight's end
// gap. (Non-linear Gauss-Seidel position sweeps were measured and retired:
// docs/dynamics.md, "Retired options".)
#pragma once

#include "dynamics/contact_row_set.h"

namespace talus {

/// Runs `iterations` sweeps of the pseudo-velocity rows of `rows` on its
/// solver bodies' pseudo velocities.
void SolveSplitImpulses(ContactRowSet& rows, int iterations);

}  // namespace talus
