// SettingNumber: how every backend writes a number into its settings list
// (harness::Setting values, shown in the report and kept in results.json).
// Header-only, because the single-precision Bullet module links no project
// library and still describes its settings the same way.
#pragma once

#include <sstream>
#include <string>

namespace talus::reference {

/// `value` with `digits` significant digits (17 by default: enough to read
/// a double back exactly, so a setting in the report is the one that ran).
inline std::string SettingNumber(double value, int digits = 17) {
  std::ostringstream out;
  out.precision(digits);
  out << value;
  return out.str();
}

}  // namespace talus::reference
