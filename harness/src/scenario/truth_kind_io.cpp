// The readers' and writers' helpers every truth kind uses (truth_kind_io.h).
#include "talus/harness/scenario/truth_kind_io.h"

#include <nlohmann/json.hpp>

#include "support/text_util.h"
#include "talus/harness/scenario/scenario.h"

namespace talus::harness {

bool TruthReader::Has(const char* field) const { return entry.contains(field); }

double TruthReader::Number(const char* field) const { return entry[field].get<double>(); }

int TruthReader::Integer(const char* field) const { return entry[field].get<int>(); }

std::string TruthReader::Text(const char* field) const { return entry[field].get<std::string>(); }

Vec3 TruthReader::Vector(const char* field) const {
  const nlohmann::json& value = entry[field];
  return Vec3(value[0].get<double>(), value[1].get<double>(), value[2].get<double>());
}

double TruthReader::Bound(const char* field) {
  bounds.emplace_back(field);
  return entry[field]["value"].get<double>();
}

int TruthReader::FindBody(const std::string& name) const {
  const auto found = bodyIndex.find(name);
  return found == bodyIndex.end() ? -1 : found->second;
}

double TruthReader::Duration() const { return world.steps * world.timeStep; }

Error TruthReader::Refuse(std::string_view field, std::string_view problem) const {
  return RefuseAt(Concat({pointer, field}), problem);
}

Error TruthReader::RefuseAt(const std::string& at, std::string_view problem) const {
  return Error{
      Concat({file, ": ", at.empty() ? std::string("(root)") : PointerForMessage(at), ": ", problem})};
}

void TruthWriter::Bound(const char* field, double value) {
  const auto reason = truth.boundReasons.find(field);
  out[field] = nlohmann::ordered_json{{"value", value},
                                      {"reason", reason == truth.boundReasons.end() ? "" : reason->second}};
}

void TruthWriter::Vector(const char* field, const Vec3& value) {
  out[field] = nlohmann::ordered_json::array({value.x(), value.y(), value.z()});
}

double ScaleSafeNorm(const Vec3& v) {
  const double scale = v.cwiseAbs().maxCoeff();
  return scale > 0.0 ? scale * (v / scale).norm() : 0.0;
}

Vec3 ScaleSafeNormalized(const Vec3& v) {
  const double scale = v.cwiseAbs().maxCoeff();
  return scale > 0.0 ? Vec3((v / scale).normalized()) : Vec3::Zero();
}

}  // namespace talus::harness
