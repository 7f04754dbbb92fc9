// Point file parsing: split into lines, strip comments, split into
// whitespace-separated tokens, and read numbers with std::from_chars (exact,
// locale independent, and it reports trailing garbage such as "1.5x").
#include "point_file.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <span>
#include <sstream>
#include <system_error>

namespace talus::cli {
namespace {

// Longest part of a bad token an error message quotes (bytes of input): a
// message must stay one readable line even for a 4 MB token.
constexpr std::size_t kQuotedPrefix = 40;

// The UTF-8 byte-order mark some editors put at the start of a text file.
constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

// Every OBJ statement that carries no point (Wavefront's list, including the
// free-form geometry and rendering ones); any other word is refused, so a
// typo such as "vv 1 2 3" cannot drop a point silently.
constexpr std::array<std::string_view, 39> kObjStatements = {
    "vt",       "vn",     "vp",         "f",         "l",      "p",     "o",    "g",    "s",     "mg",
    "mtllib",   "usemtl", "usemap",     "maplib",    "cstype", "deg",   "bmat", "step", "curv",  "curv2",
    "surf",     "parm",   "trim",       "hole",      "scrv",   "sp",    "end",  "con",  "bevel", "c_interp",
    "d_interp", "lod",    "shadow_obj", "trace_obj", "ctech",  "stech", "call", "csh",  "res"};

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

}  // namespace

std::string QuoteToken(std::string_view token) {
  std::string quoted = "'";
  const std::size_t shown = std::min(token.size(), kQuotedPrefix);
  for (std::size_t i = 0; i < shown; ++i) {
    const auto byte = static_cast<unsigned char>(token[i]);
    if (byte >= 0x20 && byte < 0x7f && byte != '\\') {
      quoted += static_cast<char>(byte);
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\x%02x", byte);
      quoted += escaped;
    }
  }
  quoted += "'";
  if (shown < token.size()) quoted += "... (" + std::to_string(token.size()) + " bytes)";
  return quoted;
}

namespace {

// Parses `tokens` as coordinates x, y, z; the caller has checked the count.
Result<Vec3> ParseCoordinates(std::span<const std::string_view> tokens, const std::string& where) {
  Vec3 point;
  for (int axis = 0; axis < 3; ++axis) {
    const std::string_view token = tokens[static_cast<std::size_t>(axis)];
    // from_chars rejects a leading '+', which text files commonly contain;
    // only one sign is allowed ("+-1" is a typo, not -1).
    const std::string_view digits = token.starts_with('+') ? token.substr(1) : token;
    if (token.starts_with('+') && (digits.starts_with('+') || digits.starts_with('-'))) {
      return Error{where + QuoteToken(token) + " is not a number (two signs)"};
    }
    double value = 0.0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    // Trailing garbage first: "1e999x" is not a number, not out of range.
    const bool whole = end == digits.data() + digits.size() && !digits.empty();
    if (error == std::errc::result_out_of_range && whole) {
      return Error{where + QuoteToken(token) + " is out of the range of a double"};
    }
    if (error != std::errc() || !whole) {
      return Error{where + QuoteToken(token) + " is not a number"};
    }
    if (!std::isfinite(value)) {
      return Error{where + "coordinate " + std::string(1, "xyz"[axis]) + " is not finite (" +
                   QuoteToken(token) + ")"};
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
  if (text.starts_with(kUtf8Bom)) text.remove_prefix(kUtf8Bom.size());
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
      if (tokens[0] != "v") {
        // Other OBJ statements carry no points; an unknown word is a typo.
        if (std::find(kObjStatements.begin(), kObjStatements.end(), tokens[0]) != kObjStatements.end())
          continue;
        return Error{where + "unknown OBJ statement " + QuoteToken(tokens[0]) +
                     " (points are 'v x y z' lines; other statements such as f, vn, vt, o, g are skipped)"};
      }
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
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) return Error{path + ": is a directory, not a point file"};
  std::ifstream file(path, std::ios::binary);
  if (!file) return Error{path + ": cannot open file"};
  std::ostringstream contents;
  contents << file.rdbuf();
  if (file.bad() || file.fail()) return Error{path + ": read error"};
  return ParsePoints(contents.str(), path, format);
}

}  // namespace talus::cli
