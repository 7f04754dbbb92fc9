// The stress envelopes as JSON, written by `talus-testbed stress` and read
// back by `talus-testbed report --stress` (talus/harness/stress/stress.h).
#include <cmath>

#include "support/json_checker.h"
#include "support/text_util.h"
#include "talus/harness/stress/stress.h"

namespace talus::harness {
namespace {

constexpr const char* kStressFormat = "talus-testbed-stress";
constexpr int kStressVersion = 1;

EnvelopeProbe ReadProbe(JsonChecker& check, const JsonValue& probe, const std::string& path) {
  EnvelopeProbe p;
  p.value = check.Number(probe, path, "value", false);
  p.pass = check.Bool(probe, path, "pass");
  p.measure = check.NumberOrNull(probe, path, "measure");
  if (const JsonValue* detail = check.Member(probe, path, "detail")) {
    if (detail->is_string()) {
      p.detail = detail->get<std::string>();
    } else {
      check.Fail(path + ".detail", "a string");
    }
  }
  return p;
}

StressEntry ReadEntry(JsonChecker& check, const JsonValue& envelope, const std::string& path) {
  StressEntry e;
  e.axis = check.Text(envelope, path, "axis");
  e.backend = check.Text(envelope, path, "backend");
  e.envelope.lastPass = check.NumberOrNull(envelope, path, "lastPass");
  e.envelope.firstFail = check.NumberOrNull(envelope, path, "firstFail");
  if (const JsonValue* probes = check.Array(envelope, path, "probes")) {
    for (std::size_t i = 0; i < probes->size() && !check.Failed(); ++i) {
      e.envelope.probes.push_back(ReadProbe(check, (*probes)[i], Indexed(path, "probes", i)));
    }
  }
  return e;
}

}  // namespace

std::string StressJson(const std::vector<StressEntry>& entries) {
  const auto number = [](double v) {
    return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json();
  };
  nlohmann::ordered_json out;
  out["format"] = kStressFormat;
  out["version"] = kStressVersion;
  out["envelopes"] = nlohmann::ordered_json::array();
  for (const StressEntry& e : entries) {
    nlohmann::ordered_json probes = nlohmann::ordered_json::array();
    for (const EnvelopeProbe& p : e.envelope.probes) {
      probes.push_back(
          {{"value", p.value}, {"pass", p.pass}, {"measure", number(p.measure)}, {"detail", p.detail}});
    }
    out["envelopes"].push_back({{"axis", e.axis},
                                {"backend", e.backend},
                                {"lastPass", number(e.envelope.lastPass)},
                                {"firstFail", number(e.envelope.firstFail)},
                                {"probes", probes}});
  }
  return out.dump(2) + "\n";
}

Result<std::vector<StressEntry>> ParseStressJson(std::string_view text, std::string_view source) {
  const JsonValue root = JsonValue::parse(text, nullptr, false);
  if (root.is_discarded()) return Error{Concat({source, ": not valid JSON"})};
  JsonChecker check;
  if (check.Text(root, "$", "format") != kStressFormat && !check.Failed()) {
    check.Fail("$.format", "\"talus-testbed-stress\"");
  }
  if (check.Integer(root, "$", "version") != kStressVersion && !check.Failed()) {
    check.Fail("$.version", "1");
  }
  std::vector<StressEntry> entries;
  if (const JsonValue* envelopes = check.Array(root, "$", "envelopes")) {
    for (std::size_t i = 0; i < envelopes->size() && !check.Failed(); ++i) {
      entries.push_back(ReadEntry(check, (*envelopes)[i], Indexed("$", "envelopes", i)));
    }
  }
  if (check.Failed()) return Error{Concat({source, ": ", check.Message()})};
  return entries;
}

Result<std::vector<StressEntry>> ReadStressFile(const std::filesystem::path& path) {
  auto text = ReadTextFile(path, "the stress envelopes");
  if (!text) return text.GetError();
  return ParseStressJson(text.Value(), path.string());
}

}  // namespace talus::harness
