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
  // Per file: its temporary, and the previous file's second name (if any).
  std::vector<fs::path> temporaries;
  std::vector<std::optional<fs::path>> previous;
  const auto discard = [&] {
    for (const fs::path& temporary : temporaries) RemoveQuietly(temporary);
    for (const std::optional<fs::path>& kept : previous) {
      if (kept) RemoveQuietly(*kept);
    }
  };
  // Every text first: a full disk or a missing folder stops the set here,
  // before any target has changed.
  for (const FileText& file : files) {
    const fs::path temporary = TemporarySibling(file.path);
    if (auto reason = WriteTemporary(temporary, file.text)) {
      discard();
      return CannotWrite(file.path, *reason);
    }
    temporaries.push_back(temporary);
  }
  for (const FileText& file : files) {
    auto kept = KeepPrevious(file.path);
    if (!kept) {
      discard();
      return kept.GetError();
    }
    previous.push_back(std::move(kept).Value());
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::error_code error;
    fs::rename(temporaries[i], files[i].path, error);
    if (!error) continue;
    // Undo the renames before this one, newest first.
    for (std::size_t j = i; j-- > 0;) {
      std::error_code ignored;
      if (previous[j]) {
        fs::rename(*previous[j], files[j].path, ignored);
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
