// The names the Talus rows give the engine's enum values: the one table of
// enum-to-text a Talus row's settings (talus_settings_text.cpp) and step
// counters (talus_backend.cpp) use. The text is what results.json records,
// so it stays as it is when an enum value is renamed.
#pragma once

#include <string>

#include "talus/world_settings.h"

namespace talus::reference {

/// The structure's name as the settings and the report's figure 2 show it.
const char* BroadPhaseName(BroadPhaseKind kind);
const char* PositionCorrectionName(PositionCorrection correction);
std::string TranslationText(TranslationIntegrator translation);
/// The sweep solver's order (the soft step is described by SolverText).
std::string ContactSolverText(ContactOrder solver);
std::string FrictionSolveText(FrictionSolve friction);
std::string BounceTimingText(BounceTiming timing);
std::string SatText(SatMode mode);
std::string ManifoldText(ManifoldMode mode);
std::string GyroscopicText(RotationIntegrator rotation);

}  // namespace talus::reference
