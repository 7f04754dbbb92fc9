// AllBackends: the one registry of every backend the testbed ships, for the
// programs (talus-testbed, talus-scenes) and the tests alike. Each backend
// declares its thread safety where it registers (harness::ThreadSafety);
// the runner reads it from here instead of guessing it from the name.
#pragma once

#include "talus/harness/backend/backend.h"

namespace talus::reference {

/// Talus's variants, Bullet (double and single precision), ODE's two
/// steppers and MuJoCo, each in its defaults and tuned configuration;
/// built once, on first use. Names() lists them sorted.
const harness::BackendRegistry& AllBackends();

/// The same backends with every Talus world on `talusThreads` threads
/// (WorldSettings::threads; a count outside [1, kMaxThreads] is refused by
/// each Talus backend when it builds a world, naming it).
harness::BackendRegistry MakeAllBackends(int talusThreads);

}  // namespace talus::reference
