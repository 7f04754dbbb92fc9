// Whole-or-nothing file writes (atomic_file.h): a uniquely named temporary
// sibling, written and closed, then renamed over the target.
#include "talus/harness/support/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "support/text_util.h"

namespace talus::harness {

std::filesystem::path TemporarySibling(const std::filesystem::path& path) {
  static std::atomic<unsigned long long> counter{0};
  std::filesystem::path temporary = path;
  temporary += Concat({".tmp-", std::to_string(static_cast<long long>(::getpid())), "-",
                       std::to_string(counter.fetch_add(1))});
  return temporary;
}

Result<std::monostate> WriteFileAtomically(const std::filesystem::path& path, std::string_view text) {
  const std::filesystem::path temporary = TemporarySibling(path);
  const auto fail = [&](const std::string& reason) -> Result<std::monostate> {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    return Error{Concat({path.string(), ": cannot write (", reason, ")"})};
  };
  {
    errno = 0;
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) return fail(errno != 0 ? std::strerror(errno) : "cannot create a file in its folder");
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();  // flushes: a full disk shows here
    if (!out) return fail(errno != 0 ? std::strerror(errno) : "write failed");
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) return fail(error.message());
  return std::monostate{};
}

namespace {

Error CannotWrite(const std::filesystem::path& path, const std::string& reason) {
  return Error{Concat({path.string(), ": cannot write (", reason, ")"})};
}

// Writes `text` to `path` as it is (a new temporary, or a device),
// checking the close, where a full disk shows. Returns the reason it
// failed, empty on success.
std::string WriteDirectly(const std::filesystem::path& path, std::string_view text, bool create) {
  errno = 0;
  std::ofstream out(path, create ? std::ios::binary | std::ios::trunc : std::ios::binary);
  if (!out) return errno != 0 ? std::strerror(errno) : "cannot open it";
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) return errno != 0 ? std::strerror(errno) : "write failed";
  return "";
}

}  // namespace

Result<std::monostate> WriteFilesAtomically(std::span<const FileToWrite> files) {
  namespace fs = std::filesystem;
  // Which targets are replaced by a rename (regular files and new names).
  std::vector<bool> renamed(files.size(), true);
  for (std::size_t i = 0; i < files.size(); ++i) {
    const fs::path& path = files[i].path;
    for (std::size_t j = 0; j < i; ++j) {
      if (files[j].path.lexically_normal() == path.lexically_normal())
        return CannotWrite(path, "named twice in one set of outputs");
    }
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    if (fs::is_directory(status)) return CannotWrite(path, "it is a folder");
    renamed[i] = !fs::exists(status) || fs::is_regular_file(status);
  }
  std::vector<fs::path> temporaries(files.size());
  const auto removeTemporaries = [&temporaries]() {
    std::error_code ignored;
    for (const fs::path& temporary : temporaries) {
      if (!temporary.empty()) fs::remove(temporary, ignored);
    }
  };
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (!renamed[i]) continue;
    temporaries[i] = TemporarySibling(files[i].path);
    const std::string reason = WriteDirectly(temporaries[i], files[i].text, true);
    if (!reason.empty()) {
      removeTemporaries();
      return CannotWrite(files[i].path, reason);
    }
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (renamed[i]) continue;
    const std::string reason = WriteDirectly(files[i].path, files[i].text, false);
    if (!reason.empty()) {
      removeTemporaries();
      return CannotWrite(files[i].path, reason);
    }
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (!renamed[i]) continue;
    std::error_code error;
    fs::rename(temporaries[i], files[i].path, error);
    if (!error) {
      temporaries[i].clear();
      continue;
    }
    removeTemporaries();
    std::error_code ignored;
    for (std::size_t j = 0; j < i; ++j) {
      if (renamed[j]) fs::remove(files[j].path, ignored);
    }
    return CannotWrite(files[i].path, error.message());
  }
  return std::monostate{};
}

}  // namespace talus::harness
