// The settings list a Talus row records (harness::Setting, shown in the
// report and kept in results.json): every engine setting as text, and for
// each that departs from the scenario's default on WorldSettings{} (the
// `talus` row's), that default and what the departure measurably changes.
#pragma once

#include <string_view>
#include <vector>

#include "talus/harness/backend/backend.h"
#include "talus/world_settings.h"

namespace talus::reference {

/// The settings of the row `variantName` running `run` with `settings`,
/// against `base`, the scenario's settings on WorldSettings{}.
std::vector<harness::Setting> TalusSettingsText(const harness::Run& run, std::string_view variantName,
                                                const WorldSettings& settings, const WorldSettings& base);

}  // namespace talus::reference
