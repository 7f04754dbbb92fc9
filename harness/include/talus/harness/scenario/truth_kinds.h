// The table of truth kinds: the one place a kind is registered. Each kind
// is one unit, its fields in truth_kinds/<kind>.h and its schema fragment,
// reader, writer and evaluator in harness/src/truth/kinds/<kind>.cpp
// (truth_kind_io.h lists the members). The loader, the writer, the
// evaluator (EvaluateTruth), the check and the schema (truth_schema.h) all
// walk this list; adding a kind is its unit plus one line here (and the
// regenerated scenarios/schema.json, which a test compares with the table).
#pragma once

#include <cstddef>
#include <type_traits>
#include <utility>
#include <variant>

#include "talus/harness/scenario/truth_kinds/angular_momentum_drift.h"
#include "talus/harness/scenario/truth_kinds/at_rest.h"
#include "talus/harness/scenario/truth_kinds/bounce_heights.h"
#include "talus/harness/scenario/truth_kinds/box_landing.h"
#include "talus/harness/scenario/truth_kinds/converged_reference.h"
#include "talus/harness/scenario/truth_kinds/energy_drift.h"
#include "talus/harness/scenario/truth_kinds/energy_not_increasing.h"
#include "talus/harness/scenario/truth_kinds/flip_period.h"
#include "talus/harness/scenario/truth_kinds/free_fall.h"
#include "talus/harness/scenario/truth_kinds/hull_rest.h"
#include "talus/harness/scenario/truth_kinds/incline_slide.h"
#include "talus/harness/scenario/truth_kinds/incline_tip.h"
#include "talus/harness/scenario/truth_kinds/max_penetration.h"
#include "talus/harness/scenario/truth_kinds/max_speed.h"
#include "talus/harness/scenario/truth_kinds/momentum_conserved.h"
#include "talus/harness/scenario/truth_kinds/moves.h"
#include "talus/harness/scenario/truth_kinds/projectile.h"
#include "talus/harness/scenario/truth_kinds/rest_height.h"
#include "talus/harness/scenario/truth_kinds/rotational_energy_drift.h"
#include "talus/harness/scenario/truth_kinds/sliding_stop.h"
#include "talus/harness/scenario/truth_kinds/stack_rest.h"
#include "talus/harness/scenario/truth_kinds/state_at.h"
#include "talus/harness/scenario/truth_kinds/topples.h"
#include "talus/harness/scenario/truth_kinds/torque_free.h"

namespace talus::harness {

/// Every truth kind, in the schema's order.
using TruthKind =
    std::variant<FreeFallTruth, SlidingStopTruth, RestHeightTruth, BounceHeightsTruth,
                 ConvergedReferenceTruth, StackRestTruth, HullRestTruth, InclineSlideTruth, InclineTipTruth,
                 TorqueFreeTruth, FlipPeriodTruth, ProjectileTruth, EnergyDriftTruth,
                 AngularMomentumDriftTruth, RotationalEnergyDriftTruth, BoxLandingTruth, AtRestTruth,
                 MovesTruth, StateAtTruth, EnergyNotIncreasingTruth, MomentumConservedTruth,
                 MaxPenetrationTruth, MaxSpeedTruth, TopplesTruth>;

/// Calls fn(std::type_identity<Kind>{}) for every kind of the table, in order.
template <class Fn>
void ForEachTruthKind(Fn&& fn) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (fn(std::type_identity<std::variant_alternative_t<I, TruthKind>>{}), ...);
  }
  (std::make_index_sequence<std::variant_size_v<TruthKind>>{});
}

}  // namespace talus::harness
