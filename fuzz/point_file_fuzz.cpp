// libFuzzer target: the point-file reader (xyz, OBJ and detection) on
// fuzzed text; fuzz_checks.h lists the invariants. A broken one aborts.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "fuzz_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const std::string failure = talus::fuzz::CheckPointFileParse(text);
  if (!failure.empty()) {
    std::fprintf(stderr, "point file invariant broken: %s\n", failure.c_str());
    std::abort();
  }
  return 0;
}
