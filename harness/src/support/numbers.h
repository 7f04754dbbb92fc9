// The numeric helpers several harness files share: the infinity and NaN
// constants, the median of a sample, and a number as JSON. One definition
// each, so that every table and file computes them the same way.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <vector>

namespace talus::harness {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The median of `values`: the middle value, or the mean of the two middle
/// ones for an even count; 0 for none. The values must not be NaN.
/// Linear time (the runner takes it over every step's time of a run).
inline double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const std::size_t mid = values.size() / 2;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(mid);
  std::nth_element(values.begin(), middle, values.end());
  double median = *middle;
  // For an even count the other middle value is the largest of the lower half.
  if (values.size() % 2 == 0) median = 0.5 * (median + *std::max_element(values.begin(), middle));
  return median;
}

/// `value` as a JSON number, or null when it is not finite (JSON has no
/// NaN or infinity).
inline nlohmann::ordered_json JsonNumber(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

}  // namespace talus::harness
