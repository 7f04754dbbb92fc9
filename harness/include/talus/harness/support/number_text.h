// FormatNumber: the one way the testbed writes a number as text (reports,
// messages, settings, run ids); FormatPrintf for a fixed printf format. Header-only, because the
// single-precision Bullet module links no project library and still writes its settings with it
// (talus/reference/setting_text.h).
#pragma once

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

namespace talus::harness {

/// `value` with up to `digits` significant digits, shortest form ("%.*g"),
/// so 17 digits read back as the same double; NaN is written "n/a".
inline std::string FormatNumber(double value, int digits = 6) {
  if (std::isnan(value)) return "n/a";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

/// `value` as the shortest text that reads back as the same double
/// (std::to_chars' shortest round trip): 0.005 is "0.005", where
/// FormatNumber(value, 17) writes "0.0050000000000000001". For a value
/// that must read back exactly but is read by people too (the time step
/// in a run id). NaN is written "n/a".
inline std::string FormatShortest(double value) {
  if (std::isnan(value)) return "n/a";
  char buffer[64];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
  return std::string(buffer, end);
}

/// `value` through a printf conversion of one double (`format` such as
/// "%.3e" or "%.2f%%"), for the fixed and scientific columns of the SAT
/// check's tables, where FormatNumber's shortest form would not line up.
inline std::string FormatPrintf(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

}  // namespace talus::harness
