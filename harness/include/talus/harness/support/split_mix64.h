// SplitMix64: the small, fully specified pseudo-random generator the
// reference benchmark scenes draw from (specified in docs/bench-scenes.md),
// so that any engine, in any language, can rebuild
// the same random scene bit for bit.
//
// The generator is Steele, Lea and Flood's SplitMix64 ("Fast splittable
// pseudorandom number generators", OOPSLA 2014), as popularised by Vigna:
// a 64-bit counter advanced by the golden-ratio increment and passed through
// a bijective mixing function. All arithmetic is modulo 2^64 (unsigned
// overflow is defined in C++), so the stream is the same on every platform.
#pragma once

#include <cstdint>

namespace talus::harness {

class SplitMix64 {
 public:
  /// A stream starting from `seed` (any 64-bit value; 0 is valid). The first
  /// Next() of the stream seeded with 0 is 0xE220A8397B1DCDAF.
  explicit SplitMix64(std::uint64_t seed) : m_state(seed) {}

  /// The next 64-bit value of the stream.
  std::uint64_t Next() {
    m_state += 0x9E3779B97F4A7C15ull;
    std::uint64_t z = m_state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  /// A uniform double in [0, 1): the top 53 bits of Next() times 2^-53,
  /// exact (every value is a multiple of 2^-53).
  double NextUniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }

  /// The current state (the value the next call will advance).
  [[nodiscard]] std::uint64_t State() const { return m_state; }

 private:
  std::uint64_t m_state;
};

}  // namespace talus::harness
