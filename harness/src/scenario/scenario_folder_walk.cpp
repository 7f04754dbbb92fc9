// LoadScenarios (scenario_loader.h): the scenario files of the paths given,
// folders walked in sorted order, each file loaded, and no scenario name
// used by two files (run ids and results are keyed by it).
#include <algorithm>
#include <map>
#include <string>
#include <utility>

#include "support/text_util.h"
#include "talus/harness/scenario/scenario_loader.h"

namespace talus::harness {
namespace {

namespace fs = std::filesystem;

// The scenario files under `folder` (recursively: *.json but schema.json),
// sorted; refused when the walk fails or finds none.
Result<std::vector<fs::path>> ScenarioFilesIn(const fs::path& folder) {
  std::error_code error;
  std::vector<fs::path> found;
  for (auto it = fs::recursive_directory_iterator(folder, error); !error && it != fs::end(it);
       it.increment(error)) {
    if (it->is_regular_file() && it->path().extension() == ".json" &&
        it->path().filename() != "schema.json") {
      found.push_back(it->path());
    }
  }
  if (error) return Error{Concat({folder.string(), ": ", error.message()})};
  if (found.empty()) {
    return Error{
        Concat({folder.string(), ": no scenario files (*.json other than schema.json) in this folder"})};
  }
  std::sort(found.begin(), found.end());
  return found;
}

// The files `paths` name: files as given, folders' files in sorted order.
Result<std::vector<fs::path>> ScenarioFiles(const std::vector<fs::path>& paths) {
  std::vector<fs::path> files;
  for (const fs::path& path : paths) {
    std::error_code error;
    if (fs::is_directory(path, error)) {
      auto found = ScenarioFilesIn(path);
      if (!found) return found.GetError();
      files.insert(files.end(), found.Value().begin(), found.Value().end());
    } else if (fs::is_regular_file(path, error)) {
      files.push_back(path);
    } else {
      return Error{Concat({path.string(), ": no such scenario file or folder"})};
    }
  }
  if (files.empty()) return Error{"no scenario files found"};
  return files;
}

}  // namespace

Result<std::vector<Run>> LoadScenarios(const std::vector<fs::path>& paths) {
  auto files = ScenarioFiles(paths);
  if (!files) return files.GetError();
  std::vector<Run> runs;
  std::map<std::string, std::string> fileOfScenario;  // two files must not share a scenario name
  for (const fs::path& file : files.Value()) {
    auto loaded = LoadScenarioFile(file);
    if (!loaded) return loaded.GetError();
    if (!loaded.Value().empty()) {
      const std::string& name = loaded.Value().front().scenario.name;
      const auto [it, added] = fileOfScenario.emplace(name, file.string());
      if (!added) {
        return Error{Concat({file.string(), ": scenario name ", Quoted(name), " is already used by ",
                             it->second, " (run ids and results are keyed by it)"})};
      }
    }
    for (Run& run : loaded.Value()) runs.push_back(std::move(run));
  }
  return runs;
}

}  // namespace talus::harness
