// What every part of the loader's mapping (a schema-valid document to the
// scenario model) shares: the refusal naming file and field, a vector
// field, and body look-up by name.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <unordered_map>

#include "talus/math.h"
#include "talus/result.h"

namespace talus::harness {

/// "<file>: <pointer as written in messages>: <problem>"; "(root)" for the
/// empty pointer.
Error FieldError(std::string_view file, const std::string& pointer, const std::string& problem);

/// A three-number array the schema has already checked.
Vec3 ReadVec3(const nlohmann::json& value);

/// Body indices by name, built once per scenario so look-ups stay linear.
using BodyIndex = std::unordered_map<std::string, int>;

/// The index of the body named `name`; -1 when there is none.
int FindBody(const BodyIndex& index, const std::string& name);

}  // namespace talus::harness
