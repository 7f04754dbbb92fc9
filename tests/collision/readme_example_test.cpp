// README's "Using the engine" example: it runs and gives the analytic depth,
// and README quotes the file verbatim (so the README cannot drift from code
// that compiles).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "package/consumer/collide_two_boxes.h"

namespace talus {
namespace readme_example_test {

std::string ReadFile(const std::string& path) {
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

TEST(ReadmeExample, GivesTheAnalyticDepth) {
  // The cube's bottom at y = 0.48, the slab's top at y = 0.5.
  EXPECT_NEAR(CollideTwoBoxes(), 0.02, 1e-12);
}

TEST(ReadmeExample, ReadmeQuotesTheExampleVerbatim) {
  const std::string root = std::string(TALUS_TEST_DATA_DIR) + "/../..";
  const std::string header = ReadFile(root + "/tests/package/consumer/collide_two_boxes.h");
  const std::string readme = ReadFile(root + "/README.md");
  const auto start = header.find("#include <talus/pair_query.h>");
  ASSERT_NE(start, std::string::npos);
  ASSERT_FALSE(readme.empty());
  EXPECT_NE(readme.find("```cpp\n" + header.substr(start) + "```"), std::string::npos)
      << "README's 'Using the engine' example differs from tests/package/consumer/collide_two_boxes.h";
}

}  // namespace readme_example_test
}  // namespace talus
