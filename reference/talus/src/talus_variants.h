// The Talus rows' variant policy: which WorldSettings each talus-* row runs
// a scenario with. Every row starts from what the scenario states on
// WorldSettings{} (ScenarioSettings) and adds its named differences
// (docs/testbed-backends.md, "The Talus rows"); the backend
// (talus_backend.cpp) builds its World from them and its settings text
// (talus_settings_text.h) lists each departure.
#pragma once

#include <array>

#include "talus/harness/backend/backend.h"
#include "talus/reference/talus_backend.h"
#include "talus/result.h"
#include "talus/world_settings.h"

namespace talus::reference {

/// Which engine options a variant uses.
enum class Variant { Defaults, WriteUp, SplitImpulses, Coloured, Soft, ManifoldFriction, CoupledFriction };

/// Every variant, in the order the rows are registered.
inline constexpr std::array<Variant, 7> kVariants = {
    Variant::Defaults, Variant::WriteUp,          Variant::SplitImpulses,  Variant::Coloured,
    Variant::Soft,     Variant::ManifoldFriction, Variant::CoupledFriction};

/// The row's backend name ("talus", "talus-writeup", ...).
const char* VariantName(Variant variant);

/// A row's settings and the scenario's on WorldSettings{} they depart from.
struct RowSettings {
  WorldSettings base;
  WorldSettings settings;
};

/// The scenario's settings and the variant's on top of them; an Error,
/// prefixed with the row's name, for a combine rule the engine lacks.
Result<RowSettings> ConfigureRow(const harness::Run& run, Variant variant,
                                 const TalusBackendOptions& options);

}  // namespace talus::reference
