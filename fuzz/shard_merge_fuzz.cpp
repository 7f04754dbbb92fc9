// libFuzzer target: shard files (read, written back) and their merge, on
// fuzzed text holding several shards separated by "----" lines
// (harness_checks.h). A broken invariant aborts.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "harness_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string failure =
      talus::fuzz::CheckShardMerge(std::string_view(reinterpret_cast<const char*>(data), size));
  if (!failure.empty()) {
    std::fprintf(stderr, "shard merge invariant broken: %s\n", failure.c_str());
    std::abort();
  }
  return 0;
}
