// Whole-or-nothing file writes (atomic_file.h): a uniquely named temporary
// sibling, written and closed, then renamed over the target.
#include "talus/harness/support/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "support/text_util.h"

namespace talus::harness {
namespace {

namespace fs = std::filesystem;

Error CannotWrite(const fs::path& path, const std::string& reason) {
  return Error{Concat({path.string(), ": cannot write (", reason, ")"})};
}

void RemoveQuietly(const fs::path& path) {
  std::error_code ignored;
  fs::remove(path, ignored);
}

// Writes `text` to `temporary` and closes it; the reason when that fails
// (the temporary is then removed).
std::optional<std::string> WriteTemporary(const fs::path& temporary, std::string_view text) {
  errno = 0;
  std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
  if (!out) return errno != 0 ? std::strerror(errno) : "cannot create a file in its folder";
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();  // flushes: a full disk shows here
  if (out) return std::nullopt;
  const std::string reason = errno != 0 ? std::strerror(errno) : "write failed";
  RemoveQuietly(temporary);
  return reason;
}

// Writes `text` into the existing non-regular file `path` (a device or a
// pipe) as it is, checking the close, where a full device shows; the
// reason when that fails.
std::optional<std::string> WriteToDevice(const fs::path& path, std::string_view text) {
  errno = 0;
  std::ofstream out(path, std::ios::binary);
  if (!out) return errno != 0 ? std::strerror(errno) : "cannot open it";
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (out) return std::nullopt;
  return errno != 0 ? std::strerror(errno) : "write failed";
}

// A second name for the file now at `path`, so it can be put back after a
// later rename of the set fails: a hard link (no copy), or a copy where the
// file system has no links. Nothing when there is no regular file there.
Result<std::optional<fs::path>> KeepPrevious(const fs::path& path) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) return std::optional<fs::path>();
  const fs::path kept = TemporarySibling(path);
  fs::create_hard_link(path, kept, error);
  if (error) {
    error.clear();
    fs::copy_file(path, kept, error);
  }
  if (error) {
    RemoveQuietly(kept);
    return CannotWrite(path, Concat({"cannot keep the previous file: ", error.message()}));
  }
  return std::optional<fs::path>(kept);
}

}  // namespace

fs::path TemporarySibling(const fs::path& path) {
  static std::atomic<unsigned long long> counter{0};
  fs::path temporary = path;
  temporary += Concat({".tmp-", std::to_string(static_cast<long long>(::getpid())), "-",
                       std::to_string(counter.fetch_add(1))});
  return temporary;
}

Result<std::monostate> WriteFileAtomically(const fs::path& path, std::string_view text) {
  const fs::path temporary = TemporarySibling(path);
  if (auto reason = WriteTemporary(temporary, text)) return CannotWrite(path, *reason);
  std::error_code error;
  fs::rename(temporary, path, error);
  if (error) {
    RemoveQuietly(temporary);
    return CannotWrite(path, error.message());
  }
  return std::monostate{};
}

Result<std::monostate> WriteFilesAtomically(const std::vector<FileText>& files) {
  // Refused before anything is written: a path named twice, or a folder.
  // A target that exists and is not a regular file (a device such as
  // /dev/stdout or /dev/full, a pipe) is written directly: renaming over
  // it would swap the device for a plain file.
  std::vector<bool> direct(files.size(), false);
  for (std::size_t i = 0; i < files.size(); ++i) {
    const fs::path& path = files[i].path;
    for (std::size_t j = 0; j < i; ++j) {
      if (files[j].path.lexically_normal() == path.lexically_normal()) {
        return CannotWrite(path, "named twice in one set of outputs");
      }
    }
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    if (fs::is_directory(status)) return CannotWrite(path, "it is a folder");
    direct[i] = fs::exists(status) && !fs::is_regular_file(status);
  }
  // Per file: its temporary (none for a direct target), and the previous
  // file's second name (if any).
  std::vector<fs::path> temporaries(files.size());
  std::vector<std::optional<fs::path>> previous;
  const auto discard = [&] {
    for (const fs::path& temporary : temporaries) {
      if (!temporary.empty()) RemoveQuietly(temporary);
    }
    for (const std::optional<fs::path>& kept : previous) {
      if (kept) RemoveQuietly(*kept);
    }
  };
  // Every text first: a full disk or a missing folder stops the set here,
  // before any regular target has changed.
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (direct[i]) continue;
    const fs::path temporary = TemporarySibling(files[i].path);
    if (auto reason = WriteTemporary(temporary, files[i].text)) {
      discard();
      return CannotWrite(files[i].path, *reason);
    }
    temporaries[i] = temporary;
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (!direct[i]) continue;
    if (auto reason = WriteToDevice(files[i].path, files[i].text)) {
      discard();
      return CannotWrite(files[i].path, *reason);
    }
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    auto kept =
        direct[i] ? Result<std::optional<fs::path>>(std::optional<fs::path>()) : KeepPrevious(files[i].path);
    if (!kept) {
      discard();
      return kept.GetError();
    }
    previous.push_back(std::move(kept).Value());
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (direct[i]) continue;
    std::error_code error;
    fs::rename(temporaries[i], files[i].path, error);
    if (!error) {
      temporaries[i].clear();
      continue;
    }
    // Undo the renames before this one, newest first.
    for (std::size_t j = i; j-- > 0;) {
      if (direct[j]) continue;
      std::error_code ignored;
      if (previous[j]) {
        fs::rename(*previous[j], files[j].path, ignored);
        previous[j].reset();
      } else {
        fs::remove(files[j].path, ignored);
      }
    }
    discard();
    return CannotWrite(files[i].path, error.message());
  }
  for (const std::optional<fs::path>& kept : previous) {
    if (kept) RemoveQuietly(*kept);
  }
  return std::monostate{};
}

}  // namespace talus::harness
