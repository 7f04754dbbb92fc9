// Whole-or-nothing file writes (atomic_file.h): a uniquely named temporary
// sibling, written and closed, then renamed over the target.
#include "talus/harness/support/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>

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

}  // namespace talus::harness
