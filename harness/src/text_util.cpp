// The out-of-line helpers of text_util.h: script-safe inlining and file
// reading.
#include "text_util.h"

#include <fstream>
#include <sstream>

namespace talus::harness {

std::string ScriptSafe(std::string text) {
  for (std::size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3)) {
    text.replace(at, 2, "<\\/");
  }
  return text;
}

Result<std::string> ReadTextFile(const std::filesystem::path& path, std::string_view what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{Concat({path.string(), ": cannot read ", what})};
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace talus::harness
