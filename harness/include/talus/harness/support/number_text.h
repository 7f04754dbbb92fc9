// FormatNumber: the one way the testbed writes a number as text (reports,
// messages, settings, run ids); FormatPrintf for a fixed printf format. Header-only, because the
// single-precision Bullet module links no project library and still writes its settings with it
// (talus/reference/setting_text.h).
#pragma once

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

/// `value` through a printf conversion of one double (`format` such as
/// "%.3e" or "%.2f%%"), for the fixed and scientific columns of the SAT
/// check's tables, where FormatNumber's shortest form would not line up.
inline std::string FormatPrintf(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

}  // namespace talus::harness
