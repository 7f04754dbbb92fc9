// libFuzzer target: BuildHull on fuzzed point sets (fuzz_checks.h says how
// the bytes become points and which invariants are checked). A broken
// invariant aborts, so libFuzzer keeps the input as a crash.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>

#include "fuzz_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto points = talus::fuzz::DecodeHullInput(std::span<const std::uint8_t>(data, size));
  const std::string failure = talus::fuzz::CheckHullBuild(points);
  if (!failure.empty()) {
    std::fprintf(stderr, "hull builder invariant broken: %s\n", failure.c_str());
    std::abort();
  }
  return 0;
}
