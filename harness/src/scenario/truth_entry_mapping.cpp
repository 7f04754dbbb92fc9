// One entry of a scenario file's "truths" to a Truth (truth_entry_mapping.h):
// the kind's own fields read by its unit through the truth-kind table
// (truth_kinds.h), the fields every kind shares read and checked here.
#include "scenario/truth_entry_mapping.h"

#include <optional>
#include <utility>

#include "scenario/scenario_mapping_support.h"
#include "support/text_util.h"
#include "talus/harness/scenario/truth_kind_io.h"
#include "talus/harness/scenario/truth_kinds.h"

namespace talus::harness {
namespace {

using nlohmann::json;

// The tolerance (required by the schema) must allow something: a truth
// whose tolerance is zero could never be met and would be judged by
// round-off. Then the gate: on for every backend unless "gate" is false or
// the backend is in "ungated" (each backend once, each with its reason).
Result<bool> MapGate(const json& entry, std::string_view file, const std::string& pointer, Truth& truth) {
  const json& tolerance = entry["tolerance"];
  truth.tolerance.absolute = tolerance.value("absolute", 0.0);
  truth.tolerance.relative = tolerance.value("relative", 0.0);
  truth.toleranceReason = tolerance.value("reason", "");
  if (truth.tolerance.absolute <= 0.0 && truth.tolerance.relative <= 0.0) {
    return FieldError(file, pointer + "/tolerance",
                      "needs absolute or relative > 0 (a truth without a tolerance is never judged)");
  }
  if (truth.toleranceReason.find_first_not_of(" \t\n") == std::string::npos) {
    return FieldError(file, pointer + "/tolerance/reason", "is empty; say where the tolerance comes from");
  }
  truth.gate = entry.value("gate", true);
  if (!entry.contains("ungated")) return true;
  for (size_t i = 0; i < entry["ungated"].size(); ++i) {
    const json& item = entry["ungated"][i];
    UngatedBackend ungated{item["backend"].get<std::string>(), item["reason"].get<std::string>()};
    const std::string where = pointer + "/ungated/" + std::to_string(i);
    for (const UngatedBackend& other : truth.ungated) {
      if (other.backend == ungated.backend) {
        return FieldError(file, where + "/backend",
                          "backend " + Quoted(ungated.backend) + " is listed twice");
      }
    }
    if (ungated.reason.empty()) return FieldError(file, where + "/reason", "must say why");
    truth.ungated.push_back(std::move(ungated));
  }
  return true;
}

// Every secondary bound the kind read carries a written reason, and gate
// false says why in "gateReason" (and only then).
Result<bool> MapBounds(const json& entry, std::string_view file, const std::string& pointer,
                       const std::vector<std::string>& bounds, Truth& truth) {
  for (const std::string& name : bounds) {
    const std::string reason = entry[name]["reason"].get<std::string>();
    if (reason.find_first_not_of(" \t\n") == std::string::npos) {
      return FieldError(file, pointer + "/" + name + "/reason", "is empty; say where the bound comes from");
    }
    truth.boundReasons[name] = reason;
  }
  if (entry.contains("gateReason")) {
    truth.gateReason = entry["gateReason"].get<std::string>();
    if (truth.gate) return FieldError(file, pointer + "/gateReason", "is given but the truth is gated");
  }
  if (!truth.gate && truth.gateReason.find_first_not_of(" \t\n") == std::string::npos) {
    return FieldError(file, pointer + "/gate",
                      "is false without a \"gateReason\" (say why no backend is held to the truth)");
  }
  return true;
}

// The kind the entry's "kind" names, read by that kind's unit (the table,
// truth_kinds.h). The schema admits only the table's names.
Result<TruthKind> ReadTruthKind(const std::string& name, TruthReader& reader) {
  std::optional<Result<TruthKind>> read;
  ForEachTruthKind([&](auto tag) {
    using Kind = typename decltype(tag)::type;
    if (read || name != Kind::kName) return;
    auto kind = Kind::Read(reader);
    read = kind ? Result<TruthKind>(TruthKind(std::move(kind).Value())) : Result<TruthKind>(kind.GetError());
  });
  if (read) return std::move(*read);
  return reader.Refuse("/kind", "no truth kind named " + Quoted(name));
}

// The entry's "published" figure: a value, or a range whose upper end is
// not below it, and who published it.
std::optional<Error> MapPublished(const json& published, std::string_view file, const std::string& pointer,
                                  Truth& truth) {
  PublishedFigure figure;
  figure.value = published["value"].get<double>();
  if (published.contains("upper")) {
    figure.upper = published["upper"].get<double>();
    if (figure.upper < figure.value) {
      return FieldError(file, pointer + "/published/upper", "is below \"value\" (the range's low end)");
    }
  }
  figure.source = published["source"].get<std::string>();
  if (figure.source.find_first_not_of(" \t\n") == std::string::npos) {
    return FieldError(file, pointer + "/published/source", "is empty; name who published the figure");
  }
  truth.published = figure;
  return std::nullopt;
}

}  // namespace

Result<Truth> MapTruth(const json& entry, const std::vector<BodySpec>& bodies, const BodyIndex& names,
                       const WorldSpec& world, std::string_view file, const std::string& pointer) {
  Truth truth;
  if (entry.contains("body")) {
    const std::string name = entry["body"].get<std::string>();
    truth.body = FindBody(names, name);
    if (truth.body < 0) return FieldError(file, pointer + "/body", "no body named " + Quoted(name));
  }
  TruthReader reader{entry, bodies, names, world, file, pointer, truth.body};
  auto kind = ReadTruthKind(entry["kind"].get<std::string>(), reader);
  if (!kind) return kind.GetError();
  truth.kind = std::move(kind).Value();
  auto gated = MapGate(entry, file, pointer, truth);
  if (!gated) return gated.GetError();
  auto bounded = MapBounds(entry, file, pointer, reader.bounds, truth);
  if (!bounded) return bounded.GetError();
  if (entry.contains("published")) {
    if (auto problem = MapPublished(entry["published"], file, pointer, truth)) return *problem;
  }
  return truth;
}

}  // namespace talus::harness
