// Reading point sets from text files for the `talus` command line.
//
// Two formats, both line based, '#' starting a comment to the end of the
// line and blank lines ignored:
//   xyz  one point per line: exactly three numbers "x y z";
//   obj  Wavefront OBJ: "v x y z [w]" lines are points, every other
//        statement (vn, vt, f, o, g, usemtl, ...) is ignored.
// Every error names the source and the 1-based line ("points.xyz:7:
// expected 3 numbers, got 2"); a read either yields every point or an error,
// never a partial list. Numbers are parsed with std::from_chars, so the
// result does not depend on the C locale; one leading '+' is allowed. An OBJ
// word that is no Wavefront statement ("vv") is refused as a typo. A
// leading UTF-8 byte-order mark is skipped. Messages quote at most the first
// 40 bytes of a bad token, with non-printable bytes escaped as \xNN.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "talus/math.h"
#include "talus/result.h"

namespace talus::cli {

/// How a point file is laid out.
enum class PointFormat {
  Auto,  ///< decide per file: ".obj" extension or a first statement starting with a letter means Obj
  Xyz,   ///< "x y z" per line
  Obj,   ///< Wavefront OBJ vertex lines "v x y z [w]"
};

/// Parses "auto", "xyz" or "obj" (as typed on the command line).
Result<PointFormat> ParsePointFormat(std::string_view text);

/// The format Auto resolves to for a file called `name` whose contents are
/// `text`: Obj for a ".obj" name (any case) or when the first statement
/// (non-blank, non-comment line) starts with a letter, else Xyz.
PointFormat DetectPointFormat(std::string_view name, std::string_view text);

/// Reads every point of `text`. `name` is used in error messages only.
/// Refuses a line that does not parse, a non-finite coordinate, and a file
/// with no points at all.
Result<std::vector<Vec3>> ParsePoints(std::string_view text, std::string_view name, PointFormat format);

/// A token as error messages quote it: in single quotes, at most its first
/// 40 bytes (then "... (N bytes)"), bytes outside printable ASCII and the
/// backslash written as \xNN.
std::string QuoteToken(std::string_view token);

/// Reads the file at `path` and parses it as ParsePoints does; errors also
/// for a directory and a file that cannot be opened or read.
Result<std::vector<Vec3>> ReadPointFile(const std::string& path, PointFormat format);

}  // namespace talus::cli
