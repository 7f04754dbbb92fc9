// FNV-1a, 64 bits (Fowler, Noll, Vo): the fingerprint the shard files use,
// for their runs (runsDigest, shard_identity.cpp) and for their own
// contents (the payload digest, shard_files.cpp). It detects accidents and
// naive edits (another scenario folder, a number changed by hand, a file
// cut short), not forgery: anyone can recompute it. A cryptographic hash
// would need a new dependency for no gain against the accidents it is for.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace talus::harness {

class Fnv1a64 {
 public:
  /// Hashes the bytes of `text`, then a separator byte, so that ("ab", "c")
  /// and ("a", "bc") differ.
  void Add(std::string_view text) {
    AddBytes(text);
    Mix(0xffU);
  }
  /// Hashes the bytes of `text` alone (no separator).
  void AddBytes(std::string_view text) {
    for (const char c : text) Mix(static_cast<unsigned char>(c));
  }
  /// The hash as 16 lowercase hex digits.
  [[nodiscard]] std::string Hex() const {
    char text[17];
    std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(m_hash));
    return text;
  }

 private:
  void Mix(unsigned byte) {
    m_hash ^= byte;
    m_hash *= 0x100000001b3ULL;
  }
  std::uint64_t m_hash = 0xcbf29ce484222325ULL;
};

}  // namespace talus::harness
