// JsonChecker: the validating walk the harness's JSON readers share
// (sat-check results, talus-scenes lines, stress envelopes).
//
// Each getter reads one member and checks its type and range; the first
// problem is kept with its JSON path and what was expected, and every
// getter returns a default afterwards, so a reader walks the whole document
// linearly and reports one clear message. A reader returns nothing unless
// the walk succeeded, so no result is ever half-read.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "support/text_util.h"

namespace talus::harness {

using JsonValue = nlohmann::json;

// Remembers the first problem met; every getter returns a default after it.
class JsonChecker {
 public:
  bool Failed() const { return !m_error.empty(); }
  const std::string& Message() const { return m_error; }

  // The member `key` of the object at `path`, or null (and a problem).
  const JsonValue* Member(const JsonValue& object, const std::string& path, const char* key) {
    if (Failed()) return nullptr;
    if (!object.is_object()) return Fail(path, "an object");
    const auto it = object.find(key);
    if (it == object.end()) {
      m_error = Concat({path, ".", key, ": missing"});
      return nullptr;
    }
    return &*it;
  }

  double Number(const JsonValue& object, const std::string& path, const char* key, bool nonNegative) {
    const JsonValue* value = Member(object, path, key);
    if (value == nullptr) return 0.0;
    if (!value->is_number() || !std::isfinite(value->get<double>()) ||
        (nonNegative && value->get<double>() < 0.0)) {
      Fail(Concat({path, ".", key}), nonNegative ? "a finite number >= 0" : "a finite number");
      return 0.0;
    }
    return value->get<double>();
  }

  long long Integer(const JsonValue& object, const std::string& path, const char* key,
                    bool nonNegative = true) {
    const JsonValue* value = Member(object, path, key);
    if (value == nullptr) return 0;
    if (!value->is_number_integer() || (nonNegative && value->get<long long>() < 0)) {
      Fail(Concat({path, ".", key}), nonNegative ? "an integer >= 0" : "an integer");
      return 0;
    }
    return value->get<long long>();
  }

  int Count(const JsonValue& object, const std::string& path, const char* key) {
    const long long value = Integer(object, path, key);
    if (value > 1000000000) {
      Fail(Concat({path, ".", key}), "a count below 1e9");
      return 0;
    }
    return static_cast<int>(value);
  }

  bool Bool(const JsonValue& object, const std::string& path, const char* key) {
    const JsonValue* value = Member(object, path, key);
    if (value == nullptr) return false;
    if (!value->is_boolean()) {
      Fail(Concat({path, ".", key}), "true or false");
      return false;
    }
    return value->get<bool>();
  }

  std::string Text(const JsonValue& object, const std::string& path, const char* key) {
    const JsonValue* value = Member(object, path, key);
    if (value == nullptr) return {};
    if (!value->is_string() || value->get<std::string>().empty()) {
      Fail(Concat({path, ".", key}), "a non-empty string");
      return {};
    }
    return value->get<std::string>();
  }

  const JsonValue* Array(const JsonValue& object, const std::string& path, const char* key) {
    const JsonValue* value = Member(object, path, key);
    if (value != nullptr && !value->is_array()) return Fail(Concat({path, ".", key}), "an array");
    return value;
  }

  /// The member `key` as a number, NaN when it is null (how the writers
  /// store a non-finite figure); missing or another type is a problem.
  double NumberOrNull(const JsonValue& object, const std::string& path, const char* key) {
    const JsonValue* value = Member(object, path, key);
    if (value == nullptr) return 0.0;
    if (value->is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (!value->is_number()) {
      Fail(Concat({path, ".", key}), "a number or null");
      return 0.0;
    }
    return value->get<double>();
  }

  /// Whether `object` has the member `key` (no problem either way).
  static bool Has(const JsonValue& object, const char* key) {
    return object.is_object() && object.contains(key);
  }

  std::nullptr_t Fail(const std::string& path, const char* expected) {
    if (!Failed()) m_error = Concat({path, ": expected ", expected});
    return nullptr;
  }

 private:
  std::string m_error;
};

/// "path.key[i]", the JSON path of an array element.
inline std::string Indexed(const std::string& path, const char* key, std::size_t i) {
  return Concat({path, ".", key, "[", std::to_string(i), "]"});
}

}  // namespace talus::harness
