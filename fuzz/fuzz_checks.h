// The invariants the fuzz targets check, apart from libFuzzer so that the
// plain test suites can replay every corpus file (tests/data/fuzz/) in a
// normal build: a fuzz finding stays a test after it is fixed.
//
// Hull builder input: the first byte picks a shape mode, the rest is read as
// little-endian doubles (see DecodeHullInput). Point-file input: the bytes
// are the file's text.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "talus/math.h"

namespace talus::fuzz {

/// `value`'s fractional part (its sign kept), 0 for NaN or infinity: how
/// the targets turn raw fuzzer bytes into coordinates of a bounded size.
inline double Fraction(double value) { return std::isfinite(value) ? std::fmod(value, 1.0) : 0.0; }

/// The point set a hull fuzz input stands for. Mode (first byte, modulo 5):
/// 0 raw doubles, three per point (NaN, inf, huge and tiny values pass
///   through unchanged, to test the refusals);
/// 1 near-coincident: a centre (the first point) plus the rest scaled into a
///   ball of radius 2^-s (s from the second byte, 0..63);
/// 2 near-collinear and 3 near-coplanar: points on a unit segment or square
///   with the other coordinates scaled by 2^-s;
/// 4 duplicates: every point of mode 0 repeated three times.
/// Modes 1-4 read coordinates as fractions (fmod 1, non-finite as 0), so the
/// points are finite and degenerate at every scale.
std::vector<Vec3> DecodeHullInput(std::span<const std::uint8_t> data);

/// Builds the hull of `points` and checks: NaN/inf input is refused; a hull
/// holds every input point within its tolerance, its vertices are input
/// points bit for bit, V - E + F = 2 and every face is convex against every
/// vertex; an error has a message that is not the builder's give-up. Empty
/// string when every check passes, else what failed.
std::string CheckHullBuild(std::span<const Vec3> points);

/// Parses `text` as xyz, OBJ and auto-detected, and checks: a success
/// yields finite points; an error names the file, is one line of printable
/// ASCII and stays short (a bad token is quoted by a short prefix). Empty
/// string when every check passes, else what failed.
std::string CheckPointFileParse(std::string_view text);

}  // namespace talus::fuzz
