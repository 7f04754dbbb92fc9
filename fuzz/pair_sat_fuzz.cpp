// libFuzzer target: CollideShapes on pairs of fuzzed hulls and boxes at
// fuzzed poses, against a brute-force SAT (pair_sat_checks.h). A broken
// invariant aborts, so libFuzzer keeps the input as a crash.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>

#include "pair_sat_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto input = talus::fuzz::DecodePairInput(std::span<const std::uint8_t>(data, size));
  const std::string failure = talus::fuzz::CheckPairSat(input);
  if (!failure.empty()) {
    std::fprintf(stderr, "pair query invariant broken: %s\n", failure.c_str());
    std::abort();
  }
  return 0;
}
