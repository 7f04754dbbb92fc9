// Scratch folders and whole-file reads, for the tests that write files and
// check what is left behind.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace talus::testing_support {

/// An empty folder `talus_<name>` in the system's temporary folder; what an
/// earlier run left there is removed first.
inline std::filesystem::path FreshScratchDir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("talus_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// The file's bytes; empty when it cannot be read.
inline std::string ReadWholeFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace talus::testing_support
