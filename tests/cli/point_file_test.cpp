// The point-file reader: both formats, detection, and every error path with
// the file name and line number in its message.
#include "point_file.h"

#include <gtest/gtest.h>

#include <string>

namespace talus::cli {
namespace point_file_test {

std::vector<Vec3> Parse(std::string_view text, PointFormat format = PointFormat::Auto) {
  auto points = ParsePoints(text, "points.xyz", format);
  EXPECT_TRUE(points) << points.GetError().message;
  return points ? points.Value() : std::vector<Vec3>{};
}

std::string ParseError(std::string_view text, PointFormat format = PointFormat::Xyz,
                       std::string_view name = "points.xyz") {
  auto points = ParsePoints(text, name, format);
  EXPECT_FALSE(points) << "expected an error for: " << text;
  return points ? std::string() : points.GetError().message;
}

std::string DataPath(const std::string& name) { return std::string(TALUS_TEST_DATA_DIR) + "/cli/" + name; }

TEST(PointFile, XyzLinesWithCommentsBlankLinesAndCrlfAreRead) {
  const auto points = Parse("# header\n\n1 2 3\r\n  -4.5\t+5e-1 6 # trailing\n\n7 8 9");
  ASSERT_EQ(points.size(), 3u);
  EXPECT_EQ(points[0], Vec3(1, 2, 3));
  EXPECT_EQ(points[1], Vec3(-4.5, 0.5, 6));
  EXPECT_EQ(points[2], Vec3(7, 8, 9));
}

TEST(PointFile, NumbersRoundTripExactly) {
  const auto points = Parse("0.1 1e-300 1.7976931348623157e308\n");
  ASSERT_EQ(points.size(), 1u);
  EXPECT_EQ(points[0], Vec3(0.1, 1e-300, 1.7976931348623157e308));
}

TEST(PointFile, ObjVertexLinesAreReadAndOtherStatementsIgnored) {
  const auto points =
      Parse("o shape\nv 1 2 3\nvn 0 0 1\nvt 0.5 0.5\nv 4 5 6 1.0\nf 1 2 3\ng group\n", PointFormat::Obj);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[1], Vec3(4, 5, 6));
}

TEST(PointFile, FormatIsDetectedByExtensionThenFirstStatement) {
  EXPECT_EQ(DetectPointFormat("mesh.OBJ", "1 2 3\n"), PointFormat::Obj);
  EXPECT_EQ(DetectPointFormat("points.txt", "# c\n\nv 1 2 3\n"), PointFormat::Obj);
  EXPECT_EQ(DetectPointFormat("points.txt", "# v 1 2 3\n-1 2 3\n"), PointFormat::Xyz);
  EXPECT_EQ(DetectPointFormat("points.txt", ""), PointFormat::Xyz);
  EXPECT_EQ(Parse("v 1 2 3\n").size(), 1u) << "auto reads OBJ content";
}

TEST(PointFile, ParsesFormatNames) {
  EXPECT_EQ(ParsePointFormat("xyz").Value(), PointFormat::Xyz);
  EXPECT_EQ(ParsePointFormat("obj").Value(), PointFormat::Obj);
  EXPECT_EQ(ParsePointFormat("auto").Value(), PointFormat::Auto);
  auto bad = ParsePointFormat("ply");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.GetError().message, "unknown point format 'ply' (expected auto, xyz or obj)");
}

TEST(PointFile, WrongCountNamesFileLineAndCounts) {
  EXPECT_EQ(ParseError("1 2 3\n4 5 6\n\n# c\n7 8 9\n1 2 3\n1 2\n"),
            "points.xyz:7: expected 3 numbers, got 2");
  EXPECT_EQ(ParseError("1 2 3 4\n"), "points.xyz:1: expected 3 numbers, got 4");
  EXPECT_EQ(ParseError("v 1 2\n", PointFormat::Obj, "m.obj"), "m.obj:1: expected 3 numbers after 'v', got 2");
  EXPECT_EQ(ParseError("v 1 2 3 4 5\n", PointFormat::Obj),
            "points.xyz:1: expected 3 numbers after 'v', got 5");
}

TEST(PointFile, NonNumbersNameTheToken) {
  EXPECT_EQ(ParseError("1 2 3\n1 two 3\n"), "points.xyz:2: 'two' is not a number");
  EXPECT_EQ(ParseError("1 2 3.5x\n"), "points.xyz:1: '3.5x' is not a number");
  EXPECT_EQ(ParseError("1 + 3\n"), "points.xyz:1: '+' is not a number");
  EXPECT_EQ(ParseError("v 1 2 3\n", PointFormat::Xyz), "points.xyz:1: expected 3 numbers, got 4");
}

TEST(PointFile, NonFiniteAndOutOfRangeCoordinatesAreRefused) {
  EXPECT_EQ(ParseError("1 nan 3\n"), "points.xyz:1: coordinate y is not finite ('nan')");
  EXPECT_EQ(ParseError("0 0 0\n1 2 inf\n"), "points.xyz:2: coordinate z is not finite ('inf')");
  EXPECT_EQ(ParseError("1e999 0 0\n"), "points.xyz:1: '1e999' is out of the range of a double");
}

TEST(PointFile, FileWithoutPointsIsRefused) {
  EXPECT_EQ(ParseError("# only a comment\n\n"), "points.xyz: no points found");
  EXPECT_EQ(ParseError("o empty\nf 1 2 3\n", PointFormat::Obj, "e.obj"),
            "e.obj: no points found (no 'v x y z' lines)");
}

TEST(PointFile, MissingFileIsRefusedWithItsPath) {
  const std::string path = std::string(TALUS_TEST_DATA_DIR) + "/cli/does_not_exist.xyz";
  auto points = ReadPointFile(path, PointFormat::Auto);
  ASSERT_FALSE(points);
  EXPECT_EQ(points.GetError().message, path + ": cannot open file");
}

TEST(PointFile, ReadsDataFiles) {
  auto cube = ReadPointFile(std::string(TALUS_TEST_DATA_DIR) + "/cli/cube.xyz", PointFormat::Auto);
  ASSERT_TRUE(cube) << cube.GetError().message;
  EXPECT_EQ(cube.Value().size(), 9u);
  auto tetra = ReadPointFile(std::string(TALUS_TEST_DATA_DIR) + "/cli/tetra.obj", PointFormat::Auto);
  ASSERT_TRUE(tetra) << tetra.GetError().message;
  EXPECT_EQ(tetra.Value().size(), 4u);
}

// Issue 14: hostile point files. Each once was accepted silently or quoted
// unreadably; the data files are in tests/data/cli.
TEST(PointFileHostile, TwoSignsAreRefused) {
  EXPECT_EQ(ParseError("1 2 3\n+-1 0 0\n"), "points.xyz:2: '+-1' is not a number (two signs)");
  EXPECT_EQ(ParseError("++1 0 0\n"), "points.xyz:1: '++1' is not a number (two signs)");
  EXPECT_EQ(ParseError("-+1 0 0\n"), "points.xyz:1: '-+1' is not a number");
  auto file = ReadPointFile(DataPath("plus_minus.xyz"), PointFormat::Auto);
  ASSERT_FALSE(file);
  EXPECT_EQ(file.GetError().message, DataPath("plus_minus.xyz") + ":3: '+-1' is not a number (two signs)");
}

TEST(PointFileHostile, UnknownObjStatementIsRefusedAsATypo) {
  auto file = ReadPointFile(DataPath("obj_typo.obj"), PointFormat::Auto);
  ASSERT_FALSE(file);
  EXPECT_EQ(file.GetError().message,
            DataPath("obj_typo.obj") +
                ":4: unknown OBJ statement 'vv' (points are 'v x y z' lines; other statements such as f, vn, "
                "vt, o, g are skipped)");
  // Every real statement is still skipped.
  EXPECT_EQ(Parse("mtllib a.mtl\nusemtl m\nv 1 2 3\nvp 0.5\ns off\nl 1 2\np 1\n", PointFormat::Obj).size(),
            1u);
}

TEST(PointFileHostile, DirectoryIsNamedAsADirectory) {
  const std::string path = std::string(TALUS_TEST_DATA_DIR) + "/cli";
  auto points = ReadPointFile(path, PointFormat::Auto);
  ASSERT_FALSE(points);
  EXPECT_EQ(points.GetError().message, path + ": is a directory, not a point file");
}

// A 4 MB token is quoted by its first 40 bytes and its length.
TEST(PointFileHostile, HugeTokenIsQuotedByAShortPrefix) {
  const std::string token(4 << 20, '7');
  const std::string message = ParseError("1 2 " + token + "x\n");
  EXPECT_EQ(message, "points.xyz:1: '" + std::string(40, '7') + "'... (" + std::to_string((4 << 20) + 1) +
                         " bytes) is not a number");
}

TEST(PointFileHostile, NulAndOtherControlBytesAreEscaped) {
  auto file = ReadPointFile(DataPath("nul_byte.xyz"), PointFormat::Auto);
  ASSERT_FALSE(file);
  EXPECT_EQ(file.GetError().message, DataPath("nul_byte.xyz") + ":3: '1\\x00' is not a number");
  EXPECT_EQ(QuoteToken("a\\b\x7f\xff"), "'a\\x5cb\\x7f\\xff'");
  EXPECT_EQ(ParseError("1 2 \xef\xbb\xbf"
                       "3\n"),
            "points.xyz:1: '\\xef\\xbb\\xbf3' is not a number");
}

// Editors on some systems start a text file with a UTF-8 byte-order mark:
// skipped at the start, so the file reads as without it.
TEST(PointFileHostile, LeadingByteOrderMarkIsSkipped) {
  auto file = ReadPointFile(DataPath("bom.xyz"), PointFormat::Auto);
  ASSERT_TRUE(file) << file.GetError().message;
  ASSERT_EQ(file.Value().size(), 4u);
  EXPECT_EQ(file.Value()[0], Vec3(0, 0, 0));
}

}  // namespace point_file_test
}  // namespace talus::cli
