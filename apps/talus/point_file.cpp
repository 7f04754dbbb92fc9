// Point file parsing: split into lines, strip comments, split into
// whitespace-separated tokens, and read numbers with std::from_chars (exact,
// locale independent, and it reports trailing garbage such as "1.5x").
#include "point_file.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <span>
#include <sstream>
#include <system_error>

namespace talus::cli {
namespace {

std::vector<std::string_view> Tokens(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

// The line without its comment.
std::string_view StripComment(std::string_view line) {
  const std::size_t hash = line.find('#');
  return hash == std::string_view::npos ? line : line.substr(0, hash);
}

std::string Where(std::string_view name, std::size_t line) {
  return std::string(name) + ":" + std::to_string(line) + ": ";
}

// Parses `tokens` as coordinates x, y, z; the caller has checked the count.
Result<Vec3> ParseCoordinates(std::span<const std::string_view> tokens, const std::string& where) {
  Vec3 point;
  for (int axis = 0; axis < 3; ++axis) {
    const std::string_view token = tokens[static_cast<std::size_t>(axis)];
    // from_chars rejects a leading '+', which text files commonly contain.
    const std::string_view digits = token.starts_with('+') ? token.substr(1) : token;
    double value = 0.0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (error == std::errc::result_out_of_range) {
      return Error{where + "'" + std::string(token) + "' is out of the range of a double"};
    }
    if (error != std::errc() || end != digits.data() + digits.size() || digits.empty()) {
      return Error{where + "'" + std::string(token) + "' is not a number"};
    }
    if (!std::isfinite(value)) {
      return Error{where + "coordinate " + std::string(1, "xyz"[axis]) + " is not finite ('" +
                   std::string(token) + "')"};
    }
    point[axis] = value;
  }
  return point;
}

}  // namespace

Result<PointFormat> ParsePointFormat(std::string_view text) {
  if (text == "auto") return PointFormat::Auto;
  if (text == "xyz") return PointFormat::Xyz;
  if (text == "obj") return PointFormat::Obj;
  return Error{"unknown point format '" + std::string(text) + "' (expected auto, xyz or obj)"};
}

PointFormat DetectPointFormat(std::string_view name, std::string_view text) {
  if (name.size() >= 4) {
    std::string extension(name.substr(name.size() - 4));
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (extension == ".obj") return PointFormat::Obj;
  }
  std::size_t begin = 0;
  while (begin <= text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string_view::npos) end = text.size();
    const auto tokens = Tokens(StripComment(text.substr(begin, end - begin)));
    if (!tokens.empty()) {
      return std::isalpha(static_cast<unsigned char>(tokens[0][0])) ? PointFormat::Obj : PointFormat::Xyz;
    }
    begin = end + 1;
  }
  return PointFormat::Xyz;
}

Result<std::vector<Vec3>> ParsePoints(std::string_view text, std::string_view name, PointFormat format) {
  if (format == PointFormat::Auto) format = DetectPointFormat(name, text);
  std::vector<Vec3> points;
  std::size_t lineNumber = 0;
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string_view::npos) end = text.size();
    ++lineNumber;
    const auto tokens = Tokens(StripComment(text.substr(begin, end - begin)));
    begin = end + 1;
    if (tokens.empty()) continue;
    const std::string where = Where(name, lineNumber);
    std::span<const std::string_view> numbers(tokens);
    if (format == PointFormat::Obj) {
      if (tokens[0] != "v") continue;  // other OBJ statements carry no points
      numbers = numbers.subspan(1);
      // OBJ allows an optional weight w after x y z.
      if (numbers.size() != 3 && numbers.size() != 4) {
        return Error{where + "expected 3 numbers after 'v', got " + std::to_string(numbers.size())};
      }
    } else if (numbers.size() != 3) {
      return Error{where + "expected 3 numbers, got " + std::to_string(numbers.size())};
    }
    auto point = ParseCoordinates(numbers, where);
    if (!point) return point.GetError();
    points.push_back(point.Value());
  }
  if (points.empty()) {
    return Error{std::string(name) + ": no points found" +
                 (format == PointFormat::Obj ? " (no 'v x y z' lines)" : "")};
  }
  return points;
}

Result<std::vector<Vec3>> ReadPointFile(const std::string& path, PointFormat format) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return Error{path + ": cannot open file"};
  std::ostringstream contents;
  contents << file.rdbuf();
  if (file.bad()) return Error{path + ": read error"};
  return ParsePoints(contents.str(), path, format);
}

}  // namespace talus::cli
