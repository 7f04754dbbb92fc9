// InRange: the range check of every numeric flag of the talus programs.
//
// CLI11's own Range, PositiveNumber and NonNegativeNumber print their
// bounds with std::to_string, so `--param -3` was refused with the 309
// digits of DBL_MAX; they let NaN through (every comparison with NaN is
// false), and CLI11 reads "-3" as an unsigned number 2^64 - 3. This check
// reads the text itself (std::from_chars: decimal only, overflow
// detected), names the value and the range in the shortest text that
// reads back to the same number, and CLI11 puts the flag in front:
//   --param: -3 is outside the range 1 to 1000
// A value that is not a number of the flag's type is refused here too, so
// the message names the range instead of a bare conversion failure.
#pragma once

#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <string>
#include <system_error>
#include <type_traits>

namespace talus::flags {

/// The shortest text that reads back to `value` (integers as integers).
template <typename T>
std::string RangeNumber(T value) {
  char buffer[64];
  const auto written = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, written.ptr);
}

/// Accepts a value of type T in [min, max] (both inclusive; with
/// `lowerOpen`, above min: for quantities that must be positive) and
/// refuses NaN, text that is not a whole decimal T, and values outside the
/// range. An accepted value is handed on to CLI11 as its shortest text, so
/// CLI11 converts the number that was checked (it would read "010" as
/// octal).
template <typename T>
CLI::Validator InRange(T min, T max, bool lowerOpen = false) {
  static_assert(std::is_arithmetic_v<T>);
  const std::string range = lowerOpen ? "above " + RangeNumber(min) + " up to " + RangeNumber(max)
                                      : RangeNumber(min) + " to " + RangeNumber(max);
  return CLI::Validator(
      [min, max, lowerOpen, range](std::string& input) -> std::string {
        const char* begin = input.data();
        const char* end = input.data() + input.size();
        if (begin != end && *begin == '+') ++begin;
        T value{};
        const bool negative = begin != end && *begin == '-';
        const auto [stop, error] = std::from_chars(begin, end, value);
        // A negative number for an unsigned flag, or one past T's own range.
        if ((std::is_unsigned_v<T> && negative) || error == std::errc::result_out_of_range) {
          return input + " is outside the range " + range;
        }
        if (error != std::errc{} || stop != end) {
          return "\"" + input + "\" is not a number in the range " + range;
        }
        bool inside = !(value < min) && !(value > max) && !(lowerOpen && !(value > min));
        if constexpr (std::is_floating_point_v<T>) inside = inside && !std::isnan(value);
        if (!inside) return input + " is outside the range " + range;
        input = RangeNumber(value);
        return {};
      },
      lowerOpen ? "(" + RangeNumber(min) + ", " + RangeNumber(max) + "]"
                : "[" + RangeNumber(min) + ", " + RangeNumber(max) + "]");
}

}  // namespace talus::flags
