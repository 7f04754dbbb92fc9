// MuJoCo's error and warning channels, turned into results.
//
// MuJoCo reports a fatal error (stack overflow, a mis-sized buffer...) by
// calling mju_user_error, whose default prints and exits the process, and a
// warning (contact buffer full, bad qacc...) by calling mju_user_warning,
// whose default prints and appends to MUJOCO_LOG.TXT in the working
// directory. InstallMujocoHandlers (once per process) replaces both: the
// warning handler only keeps the text for this thread; the error handler
// jumps back (longjmp) to the innermost Guarded call on this thread, which
// returns the message. The engine is C, so the jump crosses only C frames
// and the trivial frame of the Guarded* function itself; the mjData it
// interrupted is left half-updated and must not be stepped again (the
// backend marks the world failed). An error outside any guard aborts, which
// would be a bug here, never a silent exit.
//
// Models load from an MJCF text through a virtual file system, so nothing
// touches the disk; mj_loadXML returns its own parse and compile errors.
#pragma once

#include <mujoco/mujoco.h>

#include <string>

#include "talus/result.h"

namespace talus::reference {

/// Replaces mju_user_error and mju_user_warning (idempotent, thread-safe).
void InstallMujocoHandlers();

/// mj_step, with a MuJoCo error returned as its message ("" when none).
std::string GuardedStep(const mjModel* model, mjData* data);

/// mj_makeData, with a MuJoCo error returned as an Error.
Result<mjData*> GuardedMakeData(const mjModel* model);

/// The model of an MJCF text, or MuJoCo's parse/compile error.
Result<mjModel*> LoadMjcf(const std::string& mjcf);

/// The first warning MuJoCo raised in `data` since it was made ("" when
/// none): its kind and the count MuJoCo attached (e.g. the contact count
/// when the contact buffer was full).
std::string FirstWarning(const mjData* data);

}  // namespace talus::reference
