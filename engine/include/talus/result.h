// Result<T>: the value of an operation that can fail on bad user data.
//
// Builders and parsers return a Result instead of throwing or returning a
// half-built object: either a complete, validated value or an error message
// that says what was wrong and where. (std::expected is C++23; this is the
// small subset Talus needs.)
#pragma once

#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace talus {

/// Why an operation refused its input: a human-readable message naming what
/// and where ("point 17: coordinate is NaN").
struct Error {
  std::string message;
};

template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : m_state(std::move(value)) {}      // NOLINT: implicit by design
  Result(Error error) : m_state(std::move(error)) {}  // NOLINT: implicit by design

  [[nodiscard]] bool Ok() const { return std::holds_alternative<T>(m_state); }
  explicit operator bool() const { return Ok(); }

  /// The value; only valid when Ok().
  [[nodiscard]] const T& Value() const& {
    assert(Ok());
    return std::get<T>(m_state);
  }
  [[nodiscard]] T& Value() & {
    assert(Ok());
    return std::get<T>(m_state);
  }
  [[nodiscard]] T&& Value() && {
    assert(Ok());
    return std::get<T>(std::move(m_state));
  }

  /// The error; only valid when !Ok().
  [[nodiscard]] const Error& GetError() const {
    assert(!Ok());
    return std::get<Error>(m_state);
  }

 private:
  std::variant<T, Error> m_state;
};

}  // namespace talus
