// SettingNumber: how every backend writes a number into its settings list
// (harness::Setting values, shown in the report and kept in results.json).
// Header-only, because the single-precision Bullet module links no project
// library and still describes its settings the same way.
#pragma once

#include <string>

#include "talus/harness/support/number_text.h"

namespace talus::reference {

/// `value` with `digits` significant digits (17 by default: enough to read
/// a double back exactly, so a setting in the report is the one that ran);
/// the testbed's one number formatter, harness::FormatNumber.
inline std::string SettingNumber(double value, int digits = 17) {
  return harness::FormatNumber(value, digits);
}

}  // namespace talus::reference
