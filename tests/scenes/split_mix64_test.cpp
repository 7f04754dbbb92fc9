// SplitMix64 against the check values of docs/bench-scenes.md and an independent
// transcription of the definition.
#include "talus/harness/support/split_mix64.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

namespace talus::harness {
namespace split_mix64_test {

// The definition written out again, step by step, as the oracle.
std::uint64_t OracleNext(std::uint64_t& state) {
  state = state + 0x9E3779B97F4A7C15ull;
  std::uint64_t z = state;
  z = z ^ (z >> 30);
  z = z * 0xBF58476D1CE4E5B9ull;
  z = z ^ (z >> 27);
  z = z * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

TEST(SplitMix64, FirstValueOfSeedZeroIsTheCheckValue) {
  SplitMix64 random(0);
  EXPECT_EQ(random.Next(), 0xE220A8397B1DCDAFull);
}

TEST(SplitMix64, StateAdvancesByTheGoldenGammaPerDraw) {
  SplitMix64 random(5);
  random.Next();
  random.Next();
  EXPECT_EQ(random.State(), 5 + 2 * 0x9E3779B97F4A7C15ull);
}

TEST(SplitMix64, StreamMatchesTheDefinitionForManySeeds) {
  for (std::uint64_t seed : {0ull, 1ull, 20261122ull, 0xFFFFFFFFFFFFFFFFull, 0x8000000000000000ull}) {
    SplitMix64 random(seed);
    std::uint64_t state = seed;
    for (int i = 0; i < 1000; ++i)
      ASSERT_EQ(random.Next(), OracleNext(state)) << "seed " << seed << " draw " << i;
  }
}

TEST(SplitMix64, UniformIsTheTop53BitsTimesTwoToTheMinus53) {
  SplitMix64 random(0);
  const double expected = static_cast<double>(0xE220A8397B1DCDAFull >> 11) / 9007199254740992.0;  // 2^53
  EXPECT_EQ(random.NextUniform(), expected);
}

TEST(SplitMix64, UniformsLieInUnitIntervalWithMeanOneHalf) {
  // 100,000 draws: the mean of U[0,1) has standard deviation
  // sqrt(1/12 / 1e5) = 9.1e-4; 0.005 is more than five of them.
  SplitMix64 random(20261122);
  double sum = 0.0;
  const int count = 100000;
  for (int i = 0; i < count; ++i) {
    const double u = random.NextUniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
  }
  EXPECT_NEAR(sum / count, 0.5, 0.005);
}

}  // namespace split_mix64_test
}  // namespace talus::harness
