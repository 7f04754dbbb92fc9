// Metrics of a trajectory that are not closed-form truths: conservation
// drift for closed systems, penetration, contact counts, and the comparison
// with a converged reference run (the same backend at a smaller step).
//
// A closed system here is one with no static or kinematic body and no
// load or impulse (scenario.h): nothing outside the
// dynamic bodies exerts force but uniform gravity, so the total energy, the
// linear momentum minus M g t and the angular momentum about the system's
// centre of mass are conserved by the physics; what the engine loses or
// gains is its drift. None of these metrics has a tolerance in the file
// (checked = false) except the converged reference, whose truth carries one.
#pragma once

#include <vector>

#include "talus/harness/backend/trajectory.h"
#include "talus/harness/scenario/scenario.h"
#include "talus/harness/truth/truth_check.h"

namespace talus::harness {

/// Whether the run has no static or kinematic body, load or impulse (see above).
bool IsClosedSystem(const Run& run);

/// "energy.drift" (J, largest |E - E0| over the samples) and
/// "energy.drift_relative" (that over |E0|; NaN when E0 = 0). Closed systems only.
std::vector<MetricResult> EnergyDrift(const Trajectory& trajectory);

/// "momentum.linear_drift" (N s, largest |P - P0 - M g t|) and
/// "momentum.angular_drift" (kg m^2/s, largest change of the angular
/// momentum about the system's centre of mass). Closed systems only.
std::vector<MetricResult> MomentumDrift(const Run& run, const Trajectory& trajectory);

/// "penetration.max" (m): the largest contact depth over the samples.
MetricResult MaxPenetration(const Trajectory& trajectory);

/// "contacts.final": contact points after the last step (unitless count).
MetricResult FinalContacts(const Trajectory& trajectory);

/// "converged_reference.position" (m: largest distance between the body
/// origins of `trajectory` and `reference` at common times) and
/// "converged_reference.orientation" (rad: largest rotation angle between
/// their orientations), over `truth.body` or, when -1, every body. The
/// position is judged against the truth's tolerance; the orientation is
/// reported only. Samples are matched by time (to 1e-9 s).
std::vector<MetricResult> CompareWithReference(const Truth& truth, const Trajectory& trajectory,
                                               const Trajectory& reference);

}  // namespace talus::harness
