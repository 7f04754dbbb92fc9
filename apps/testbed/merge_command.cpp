// `talus-testbed merge`: the shard files of one `sweep --shard i/n`
// partition combined into the results file an unsharded sweep writes, plus
// its sweep analysis.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <utility>

#include "sweep_commands.h"
#include "talus/harness/run/results_file.h"
#include "talus/harness/sweep/sweep.h"
#include "testbed_commands.h"

namespace talus::testbed {
namespace {

namespace fs = std::filesystem;

struct MergeOptions {
  std::vector<std::string> shards;
  std::string out = "reports/sweep";
};

int Merge(const MergeOptions& options) {
  std::vector<harness::ShardFile> shards;
  for (const std::string& path : options.shards) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      std::cerr << "talus-testbed: " << path << ": cannot read\n";
      return kExitBadInput;
    }
    std::ostringstream text;
    text << in.rdbuf();
    auto shard = harness::ShardFromJson(text.str());
    if (!shard) {
      std::cerr << "talus-testbed: " << path << ": " << shard.GetError().message << "\n";
      return kExitBadInput;
    }
    shards.push_back(std::move(shard).Value());
  }
  // Each job once across the shards: a (run, backend) pair in two files
  // (or twice in one) would be a duplicated run in the merged results.
  std::map<std::pair<std::string, std::string>, std::string> firstFile;
  for (std::size_t s = 0; s < shards.size(); ++s) {
    for (const harness::RunResult& result : shards[s].results.results) {
      const auto [at, inserted] =
          firstFile.emplace(std::pair{result.runId, result.backend}, options.shards[s]);
      if (inserted) continue;
      std::cerr << "talus-testbed: run \"" << result.runId << "\" on backend \"" << result.backend
                << "\" is in both " << at->second << " and " << options.shards[s]
                << " (each job belongs to one shard, once)\n";
      return kExitBadInput;
    }
  }
  auto merged = harness::MergeShards(shards);
  if (!merged) {
    std::cerr << "talus-testbed: " << merged.GetError().message << "\n";
    return kExitBadInput;
  }
  const std::vector<harness::SweepGroup> groups =
      harness::AnalyseSweep(merged.Value(), harness::kSweepSingleSetting);
  const fs::path out(options.out);
  std::vector<harness::FileText> files = harness::ResultsFileTexts(out / "results.json", merged.Value());
  files.push_back({out / "sweep.json", harness::SweepToJson(groups)});
  files.push_back({out / "sweep.md", harness::SweepMarkdown(groups)});
  if (!WriteTexts(files)) return kExitBadInput;
  std::cout << "merged " << shards.size() << " shards: " << merged.Value().results.size()
            << " results\nresults: " << (fs::path(options.out) / "results.json").string() << "\n";
  return kExitOk;
}

}  // namespace

void AddMergeCommand(CLI::App& app, CommandAction& chosen) {
  auto options = std::make_shared<MergeOptions>();
  CLI::App* command = app.add_subcommand("merge", "combine the shard files of a sharded sweep");
  command->add_option("shards", options->shards, "every shard file of one partition")->required();
  command->add_option("-o,--out", options->out, "output folder")->capture_default_str();
  command->callback([options, &chosen] { chosen = [options] { return Merge(*options); }; });
}

}  // namespace talus::testbed
