// Output files that are never half-written (docs/testbed-runner.md,
// "Output files"): the text goes to a temporary file with a unique name in
// the target's own folder and is renamed over the target only once it has
// been written and closed without error. rename(2) within one file system
// replaces the target in one step, so a reader, a crash, a full disk or a
// second program writing the same file at the same moment sees either the
// old file or one complete new one, never a mixture or a truncated file.
// Every file the testbed programs write goes through WriteFileAtomically,
// or WriteFilesAtomically for a set of files that belong together.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "talus/result.h"

namespace talus::harness {

/// Writes `text` to `path` as described above. The folder must exist. On
/// failure returns "<path>: cannot write (<reason>)", removes the
/// temporary file and leaves any existing `path` untouched.
Result<std::monostate> WriteFileAtomically(const std::filesystem::path& path, std::string_view text);

/// One file of a set: where it goes and its whole text.
struct FileText {
  std::filesystem::path path;
  std::string text;
};

/// Writes every file of `files` or none of them (a report's summary.md,
/// results.csv and report.html; talus-sat-check's JSON and Markdown). A set
/// naming one path twice, or a path that is a folder, is refused before
/// anything is written. Every text for a regular target (a new name or an
/// existing regular file) is first written to its temporary sibling, so a
/// full disk fails before any target changes; a target that exists and is
/// not a regular file (a device such as /dev/stdout or /dev/full, a pipe)
/// is written directly, since renaming over it would swap the device for a
/// plain file. Then the temporaries are renamed into place one by one. If a
/// rename fails, the files already renamed are put back as they were (the
/// previous file, kept as a hard link, or no file where there was none). On
/// failure returns the first failing file's error ("<path>: cannot write
/// (<reason>)"), and no temporary is left behind. The folders must exist.
Result<std::monostate> WriteFilesAtomically(const std::vector<FileText>& files);

/// The temporary name WriteFileAtomically uses for `path`: "<name>.tmp-"
/// then the process id and a per-process counter, so two writers (threads
/// or processes) never share one.
std::filesystem::path TemporarySibling(const std::filesystem::path& path);

}  // namespace talus::harness
