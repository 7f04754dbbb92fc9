// libFuzzer target: the scenario loader (JSON syntax, schema, semantic
// checks, sweep expansion) on fuzzed text, and the save-and-reload round
// trip of whatever loads (harness_checks.h). A broken invariant aborts.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "harness_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string failure =
      talus::fuzz::CheckScenarioRoundTrip(std::string_view(reinterpret_cast<const char*>(data), size));
  if (!failure.empty()) {
    std::fprintf(stderr, "scenario loader invariant broken: %s\n", failure.c_str());
    std::abort();
  }
  return 0;
}
