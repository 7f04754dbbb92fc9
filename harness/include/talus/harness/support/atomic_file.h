// Output files that are never half-written (docs/testbed-runner.md,
// "Output files"): the text goes to a temporary file with a unique name in
// the target's own folder and is renamed over the target only once it has
// been written and closed without error. rename(2) within one file system
// replaces the target in one step, so a reader, a crash, a full disk or a
// second program writing the same file at the same moment sees either the
// old file or one complete new one, never a mixture or a truncated file.
// Every file the testbed programs write goes through WriteFileAtomically.
#pragma once

#include <filesystem>
#include <string_view>
#include <variant>

#include "talus/result.h"

namespace talus::harness {

/// Writes `text` to `path` as described above. The folder must exist. On
/// failure returns "<path>: cannot write (<reason>)", removes the
/// temporary file and leaves any existing `path` untouched.
Result<std::monostate> WriteFileAtomically(const std::filesystem::path& path, std::string_view text);

/// The temporary name WriteFileAtomically uses for `path`: "<name>.tmp-"
/// then the process id and a per-process counter, so two writers (threads
/// or processes) never share one.
std::filesystem::path TemporarySibling(const std::filesystem::path& path);

}  // namespace talus::harness
