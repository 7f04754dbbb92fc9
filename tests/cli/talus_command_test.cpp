// End-to-end runs of the built `talus` binary (TALUS_CLI_BINARY) on the
// files in tests/data/cli: output text, exit codes, error messages, and that
// a failed run leaves --output untouched.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace talus::cli {
namespace talus_command_test {

namespace fs = std::filesystem;

struct RunResult {
  int exitCode = -1;
  std::string out;
  std::string err;
};

std::string Slurp(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

fs::path DataFile(const std::string& name) { return fs::path(TALUS_TEST_DATA_DIR) / "cli" / name; }

// A scratch folder per test (and one per purpose), named after the test.
fs::path Scratch(const std::string& purpose = "files") {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(::testing::TempDir()) / "talus_cli" / info->name() / purpose;
  fs::create_directories(dir);
  return dir;
}

// Runs `talus` with `args` (already shell-quoted where needed) from the
// data folder, so messages show the short file names.
RunResult RunTalus(const std::string& args) {
  const fs::path dir = Scratch("run");
  const std::string command = "cd '" + DataFile("").string() + "' && '" + std::string(TALUS_CLI_BINARY) +
                              "' " + args + " >'" + (dir / "out").string() + "' 2>'" +
                              (dir / "err").string() + "'";
  const int status = std::system(command.c_str());
  RunResult result;
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = Slurp(dir / "out");
  result.err = Slurp(dir / "err");
  return result;
}

std::vector<std::vector<std::string>> Statements(const std::string& text, const std::string& keyword) {
  std::vector<std::vector<std::string>> found;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::vector<std::string> tokens;
    for (std::string w; words >> w;) tokens.push_back(w);
    if (!tokens.empty() && tokens[0] == keyword) found.emplace_back(tokens.begin() + 1, tokens.end());
  }
  return found;
}

TEST(TalusHull, CubeFileGivesEightVerticesAndSixQuadsAsObj) {
  const RunResult run = RunTalus("hull cube.xyz");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.err, "");
  const auto vertices = Statements(run.out, "v");
  const auto faces = Statements(run.out, "f");
  ASSERT_EQ(vertices.size(), 8u);
  ASSERT_EQ(faces.size(), 6u);
  for (const auto& v : vertices) {
    for (const std::string& c : v) EXPECT_TRUE(c == "0" || c == "1") << "corner coordinate " << c;
  }
  for (const auto& f : faces) {
    ASSERT_EQ(f.size(), 4u);
    for (const std::string& index : f) {
      EXPECT_GE(std::stoi(index), 1) << "OBJ indices are 1-based";
      EXPECT_LE(std::stoi(index), 8);
    }
  }
}

// Unit cube of density 2: mass 2, centre (0.5, 0.5, 0.5), inertia
// m (1 + 1) / 12 = 1/3 on the diagonal. Tolerance 1e-12: round-off only.
TEST(TalusHull, JsonReportsVolumeMassCentreAndInertia) {
  const RunResult run = RunTalus("hull cube.xyz --format json --density 2");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["vertices"].size(), 8u);
  EXPECT_EQ(json["faces"].size(), 6u);
  EXPECT_NEAR(json["volume"].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(json["mass"].get<double>(), 2.0, 1e-12);
  EXPECT_EQ(json["density"].get<double>(), 2.0);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(json["centerOfMass"][i].get<double>(), 0.5, 1e-12);
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(json["inertia"][i][j].get<double>(), i == j ? 1.0 / 3.0 : 0.0, 1e-12);
    }
  }
}

// The corner tetrahedron with legs 2: volume 8/6, default density 1000.
TEST(TalusHull, ObjInputIsDetectedAndDefaultDensityIsWater) {
  const RunResult run = RunTalus("hull tetra.obj --format json");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["faces"].size(), 4u);
  EXPECT_NEAR(json["volume"].get<double>(), 4.0 / 3.0, 1e-12);
  EXPECT_NEAR(json["mass"].get<double>(), 4000.0 / 3.0, 1e-9);
}

TEST(TalusHull, OutputFileHoldsExactlyWhatStdoutWould) {
  const fs::path out = Scratch() / "cube.obj";
  const RunResult toFile = RunTalus("hull cube.xyz --output '" + out.string() + "'");
  ASSERT_EQ(toFile.exitCode, 0) << toFile.err;
  EXPECT_EQ(toFile.out, "");
  EXPECT_EQ(Slurp(out), RunTalus("hull cube.xyz").out);
}

// Eight runs writing one output at once: each writes its own temporary file
// (FILE.tmp-<pid>-<n>) and renames it into place, so every run succeeds,
// the output is one complete hull and no temporary file is left. With one
// fixed temporary name the runs truncated each other's file and the losers'
// renames failed (issue 14).
TEST(TalusHull, ConcurrentRunsWritingOneOutputNeverShareATemporaryFile) {
  const fs::path dir = Scratch();
  const fs::path out = dir / "cube.obj";
  const fs::path script = Scratch("script") / "race.sh";
  {
    std::ofstream file(script);
    file << "cd '" << DataFile("").string() << "' || exit 2\nstatus=0\npids=\n"
         << "for i in 1 2 3 4 5 6 7 8; do '" << TALUS_CLI_BINARY << "' hull cube.xyz -o '" << out.string()
         << "' & pids=\"$pids $!\"; done\n"
         << "for p in $pids; do wait \"$p\" || status=1; done\nexit $status\n";
  }
  const int status = std::system(("bash '" + script.string() + "'").c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "a concurrent run failed";
  EXPECT_EQ(Slurp(out), RunTalus("hull cube.xyz").out);
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename(), "cube.obj") << "left behind: " << entry.path();
  }
}

TEST(TalusHull, BadLineIsReportedWithFileAndLineAndOutputIsLeftAlone) {
  const fs::path out = Scratch() / "keep.obj";
  std::ofstream(out) << "previous contents\n";
  const RunResult run = RunTalus("hull short_line.xyz --output '" + out.string() + "'");
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find("short_line.xyz:7: expected 3 numbers, got 2"), std::string::npos) << run.err;
  EXPECT_EQ(Slurp(out), "previous contents\n");
  EXPECT_FALSE(fs::exists(out.string() + ".talus-tmp")) << "no temporary file left behind";
}

TEST(TalusHull, ForcedInputFormatOverridesDetection) {
  const RunResult run = RunTalus("hull tetra.obj --input-format xyz");
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find("tetra.obj:2: expected 3 numbers, got 2"), std::string::npos) << run.err;
}

TEST(TalusHull, CoplanarPointsReportTheBuilderError) {
  const RunResult run = RunTalus("hull flat.xyz");
  EXPECT_NE(run.exitCode, 0);
  EXPECT_EQ(run.out, "");
  EXPECT_NE(run.err.find("flat.xyz: no hull: "), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("coplanar"), std::string::npos) << run.err;
}

TEST(TalusHull, MaxVerticesCapsTheHull) {
  // 200 points on a sphere: all are hull vertices without a cap.
  const fs::path points = Scratch() / "sphere.xyz";
  {
    std::ofstream file(points);
    file.precision(17);
    for (int i = 0; i < 200; ++i) {
      const double z = 1.0 - (2.0 * i + 1.0) / 200.0;
      const double phi = i * std::numbers::pi * (3.0 - std::sqrt(5.0));
      const double s = std::sqrt(1.0 - z * z);
      file << s * std::cos(phi) << " " << s * std::sin(phi) << " " << z << "\n";
    }
  }
  const RunResult all = RunTalus("hull '" + points.string() + "'");
  ASSERT_EQ(all.exitCode, 0) << all.err;
  EXPECT_EQ(Statements(all.out, "v").size(), 200u);
  const RunResult capped = RunTalus("hull '" + points.string() + "' --max-vertices 12");
  ASSERT_EQ(capped.exitCode, 0) << capped.err;
  EXPECT_LE(Statements(capped.out, "v").size(), 12u);
  EXPECT_GE(Statements(capped.out, "v").size(), 4u);
}

TEST(TalusHull, BadOptionsExitNonZeroWithAMessage) {
  for (const std::string args : {"hull cube.xyz --format xml", "hull", "hull cube.xyz --max-vertices 3",
                                 "hull cube.xyz --density -1", "hull missing.xyz", ""}) {
    const RunResult run = RunTalus(args);
    EXPECT_NE(run.exitCode, 0) << args;
    EXPECT_EQ(run.out.find("v "), std::string::npos) << args;
    EXPECT_FALSE(run.err.empty()) << args;
  }
  EXPECT_NE(RunTalus("hull missing.xyz").err.find("missing.xyz: cannot open file"), std::string::npos);
}

}  // namespace talus_command_test
}  // namespace talus::cli
