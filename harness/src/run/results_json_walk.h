// The checked walk results.json's readers share (results_file.cpp, and
// results_tables.cpp for the tables at its top): each getter reads one
// member, checks its type and throws ResultsParseFailure naming the place
// ("/results/3/metrics/0: missing field \"measured\""). The exception never
// leaves the results reader: ParseResults turns it into an Error.
#pragma once

#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/text_util.h"

namespace talus::harness::results_json {

using Json = nlohmann::ordered_json;

/// A malformed document: where and what.
struct ResultsParseFailure {
  std::string message;
};

inline const Json& Field(const Json& object, const char* key, const std::string& where) {
  if (!object.is_object()) throw ResultsParseFailure{Concat({where, ": expected an object"})};
  const auto it = object.find(key);
  if (it == object.end()) throw ResultsParseFailure{Concat({where, ": missing field \"", key, "\""})};
  return *it;
}

inline std::string Place(const std::string& where, const char* key) { return Concat({where, "/", key}); }

/// A number; null reads as NaN (how the writer puts NaN).
inline double GetNumber(const Json& object, const char* key, const std::string& where) {
  const Json& value = Field(object, key, where);
  if (value.is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (!value.is_number()) throw ResultsParseFailure{Concat({Place(where, key), ": expected a number"})};
  return value.get<double>();
}

inline int GetInt(const Json& object, const char* key, const std::string& where) {
  const Json& value = Field(object, key, where);
  if (!value.is_number_integer())
    throw ResultsParseFailure{Concat({Place(where, key), ": expected an integer"})};
  return value.get<int>();
}

inline std::string GetString(const Json& object, const char* key, const std::string& where) {
  const Json& value = Field(object, key, where);
  if (!value.is_string()) throw ResultsParseFailure{Concat({Place(where, key), ": expected a string"})};
  return value.get<std::string>();
}

inline bool GetBool(const Json& object, const char* key, const std::string& where) {
  const Json& value = Field(object, key, where);
  if (!value.is_boolean()) throw ResultsParseFailure{Concat({Place(where, key), ": expected true or false"})};
  return value.get<bool>();
}

inline const Json& GetArray(const Json& object, const char* key, const std::string& where) {
  const Json& value = Field(object, key, where);
  if (!value.is_array()) throw ResultsParseFailure{Concat({Place(where, key), ": expected an array"})};
  return value;
}

/// Numbers; each null reads as NaN.
inline std::vector<double> GetNumbers(const Json& object, const char* key, const std::string& where) {
  std::vector<double> numbers;
  const Json& array = GetArray(object, key, where);
  for (const Json& value : array) {
    if (value.is_null()) {
      numbers.push_back(std::numeric_limits<double>::quiet_NaN());
    } else if (value.is_number()) {
      numbers.push_back(value.get<double>());
    } else {
      throw ResultsParseFailure{Concat({Place(where, key), ": expected numbers"})};
    }
  }
  return numbers;
}

}  // namespace talus::harness::results_json
