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
#include <span>
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

/// One file of a set written by WriteFilesAtomically.
struct FileToWrite {
  std::filesystem::path path;
  std::string_view text;
};

/// Writes every file of `files` or none of them (a program's outputs as
/// one set: a report never beside a missing summary). In order:
/// 1. refuses a set naming one path twice, or a path that is a folder;
/// 2. writes each regular target (new or an existing regular file) to its
///    TemporarySibling;
/// 3. writes each target that exists and is not a regular file (a device
///    such as /dev/stdout or /dev/full, a pipe) directly: it cannot be
///    replaced by a rename, and renaming over it would swap the device
///    for a plain file;
/// 4. renames the temporaries over their targets, in order.
/// A failure in 1-3 removes every temporary and leaves every regular
/// target as it was; a failed rename in 4 also removes the targets
/// already renamed, so no partial set is left (their old contents are
/// gone then). Returns "<path>: cannot write (<reason>)" for the first
/// file that failed.
Result<std::monostate> WriteFilesAtomically(std::span<const FileToWrite> files);

}  // namespace talus::harness
