// The larger and smaller of two measured values with NaN kept: std::max(a,
// NaN) is a and std::min(1.0, NaN) is 1.0, so a value that could not be
// measured would vanish from a running maximum and the metric built on it
// would pass. Every running extreme over metric values goes through these,
// so a NaN makes the metric NaN, and a NaN metric fails (truth_check.h Judge).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace talus::harness {

/// max(a, b), NaN when either is NaN.
inline double MaxKeepingNaN(double a, double b) {
  return std::isnan(a) || std::isnan(b) ? std::numeric_limits<double>::quiet_NaN() : std::max(a, b);
}

/// min(a, b), NaN when either is NaN.
inline double MinKeepingNaN(double a, double b) {
  return std::isnan(a) || std::isnan(b) ? std::numeric_limits<double>::quiet_NaN() : std::min(a, b);
}

}  // namespace talus::harness
