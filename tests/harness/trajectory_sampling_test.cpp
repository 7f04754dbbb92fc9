// Which steps a run records and which samples a plot or a replay keeps
// (talus/harness/backend/trajectory.h): the stride bound, and SpreadIndices,
// the one thinning rule the plot series and the replay frames share.
#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

#include "talus/harness/backend/trajectory.h"

namespace talus::harness {
namespace trajectory_sampling_test {

using Indices = std::vector<std::size_t>;

TEST(TrajectorySampling, StrideKeepsARunToItsSampleBudget) {
  EXPECT_EQ(SampleStride(100, 2000), 1);
  EXPECT_EQ(SampleStride(2000, 2000), 1);
  EXPECT_EQ(SampleStride(2001, 2000), 2);
  // No overflow near the step limit: ceil(2^31-1 / 2) without steps + max.
  EXPECT_EQ(SampleStride(2147483647, 2), 1073741824);
  EXPECT_TRUE(IsSampled(10, 25, 5));
  EXPECT_FALSE(IsSampled(11, 25, 5));
  EXPECT_TRUE(IsSampled(25, 25, 7)) << "the last step is always recorded";
}

TEST(TrajectorySampling, SpreadIndicesKeepTheEndsAndSpreadTheRestEvenly) {
  EXPECT_EQ(SpreadIndices(5, 3), (Indices{0, 2, 4}));
  EXPECT_EQ(SpreadIndices(11, 3), (Indices{0, 5, 10}));
  EXPECT_EQ(SpreadIndices(3, 10), (Indices{0, 1, 2})) << "fewer samples than the budget: all of them";
  EXPECT_EQ(SpreadIndices(10, 1), (Indices{0})) << "a budget of one keeps the first";
  EXPECT_TRUE(SpreadIndices(0, 5).empty());
}

TEST(TrajectorySampling, SpreadIndicesAreIncreasingWithinBudgetForEveryCount) {
  for (std::size_t count = 1; count <= 300; ++count) {
    for (std::size_t most : {2u, 3u, 7u, 120u, 200u}) {
      const Indices kept = SpreadIndices(count, most);
      ASSERT_FALSE(kept.empty());
      EXPECT_LE(kept.size(), most);
      EXPECT_EQ(kept.front(), 0u);
      EXPECT_EQ(kept.back(), count - 1) << count << " samples, " << most << " kept";
      for (std::size_t i = 1; i < kept.size(); ++i) EXPECT_LT(kept[i - 1], kept[i]);
      // Evenly spread: no gap wider than ceil((count - 1) / (kept - 1)) + 1.
      if (kept.size() >= 2) {
        const std::size_t widest = (count - 1 + kept.size() - 2) / (kept.size() - 1) + 1;
        for (std::size_t i = 1; i < kept.size(); ++i) EXPECT_LE(kept[i] - kept[i - 1], widest);
      }
    }
  }
}

}  // namespace trajectory_sampling_test
}  // namespace talus::harness
