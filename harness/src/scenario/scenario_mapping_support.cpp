// The loader's shared mapping helpers (scenario_mapping_support.h).
#include "scenario/scenario_mapping_support.h"

#include "support/text_util.h"

namespace talus::harness {

Error FieldError(std::string_view file, const std::string& pointer, const std::string& problem) {
  return Error{Concat(
      {file, ": ", pointer.empty() ? std::string("(root)") : PointerForMessage(pointer), ": ", problem})};
}

Vec3 ReadVec3(const nlohmann::json& value) {
  return Vec3(value[0].get<double>(), value[1].get<double>(), value[2].get<double>());
}

int FindBody(const BodyIndex& index, const std::string& name) {
  const auto found = index.find(name);
  return found == index.end() ? -1 : found->second;
}

}  // namespace talus::harness
