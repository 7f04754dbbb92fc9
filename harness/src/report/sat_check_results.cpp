// Reading the sat-check JSON (docs/collision-validation.md, "JSON format")
// and the report's Markdown section made from it (sat_check_results.h).
//
// The reader walks the parsed document with a small checker that keeps
// the first problem (its JSON path and what was expected) and returns
// defaults afterwards, so the walk stays linear and a bad file yields one
// clear message; nothing is returned unless the whole walk succeeded.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "support/json_checker.h"
#include "support/text_util.h"
#include "talus/harness/report/sat_check_results.h"

namespace talus::harness {
namespace {

SatDistribution ReadDistribution(JsonChecker& check, const JsonValue& method, const std::string& path,
                                 const char* key) {
  SatDistribution d;
  const JsonValue* object = check.Member(method, path, key);
  if (object == nullptr) return d;
  const std::string at = Concat({path, ".", key});
  d.count = check.Count(*object, at, "count");
  d.p50 = check.Number(*object, at, "p50", true);
  d.p90 = check.Number(*object, at, "p90", true);
  d.p99 = check.Number(*object, at, "p99", true);
  d.max = check.Number(*object, at, "max", true);
  return d;
}

std::vector<SatCase> ReadCases(JsonChecker& check, const JsonValue& method, const std::string& path,
                               const char* key) {
  std::vector<SatCase> cases;
  const JsonValue* array = check.Array(method, path, key);
  if (array == nullptr) return cases;
  for (std::size_t i = 0; i < array->size() && !check.Failed(); ++i) {
    const std::string at = Indexed(path, key, i);
    SatCase c;
    c.pair = check.Count((*array)[i], at, "pair");
    c.configuration = check.Text((*array)[i], at, "configuration");
    c.trueSignedDistance = check.Number((*array)[i], at, "trueSignedDistance", false);
    c.methodIntersecting = check.Bool((*array)[i], at, "methodIntersecting");
    c.value = check.Number((*array)[i], at, "value", true);
    cases.push_back(std::move(c));
  }
  return cases;
}

std::vector<std::pair<std::string, int>> ReadCounts(JsonChecker& check, const JsonValue& root,
                                                    const char* key) {
  std::vector<std::pair<std::string, int>> counts;
  const JsonValue* object = check.Member(root, "$", key);
  if (object == nullptr) return counts;
  if (!object->is_object()) return check.Fail(Concat({"$.", key}), "an object"), counts;
  for (const auto& [name, value] : object->items()) {
    counts.emplace_back(name, check.Count(*object, Concat({"$.", key}), name.c_str()));
  }
  return counts;
}

SatMethod ReadMethod(JsonChecker& check, const JsonValue& method, const std::string& path) {
  SatMethod m;
  m.name = check.Text(method, path, "name");
  m.family = check.Text(method, path, "family");
  m.givesDepth = check.Bool(method, path, "givesDepth");
  if (const JsonValue* verdict = check.Member(method, path, "verdict")) {
    const std::string at = path + ".verdict";
    m.agree = check.Count(*verdict, at, "agree");
    m.disagree = check.Count(*verdict, at, "disagree");
    m.touchingBandDisagree = check.Count(*verdict, at, "touchingBandDisagree");
    m.oracleFailures = check.Count(*verdict, at, "oracleFailures");
  }
  m.depthError = ReadDistribution(check, method, path, "depthError");
  m.normalAngle = ReadDistribution(check, method, path, "normalAngle");
  m.normalExcess = ReadDistribution(check, method, path, "normalExcess");
  m.timeNs = ReadDistribution(check, method, path, "timeNs");
  m.disagreements = ReadCases(check, method, path, "disagreements");
  m.worstDepth = ReadCases(check, method, path, "worstDepth");
  m.worstNormal = ReadCases(check, method, path, "worstNormal");
  return m;
}

std::string Percentiles(const SatDistribution& d) {
  if (d.count == 0) return "-";
  return Concat({FormatPrintf("%.1e", d.p50), " / ", FormatPrintf("%.1e", d.p90), " / ",
                 FormatPrintf("%.1e", d.p99), " / ", FormatPrintf("%.1e", d.max)});
}

// How many of each method's worst depth and normal cases are listed.
constexpr std::size_t kWorstListed = 3;

void WorstRows(std::ostringstream& out, const SatMethod& m, const char* kind,
               const std::vector<SatCase>& cases, std::size_t limit, const char* unit) {
  for (std::size_t i = 0; i < cases.size() && i < limit; ++i) {
    const SatCase& c = cases[i];
    out << "| " << m.name << " | " << kind << " | " << c.pair << " | `" << c.configuration << "` | "
        << FormatPrintf("%.3e", c.trueSignedDistance) << " | " << (c.methodIntersecting ? "yes" : "no")
        << " | " << (unit[0] == '\0' ? std::string("-") : Concat({FormatPrintf("%.3e", c.value), " ", unit}))
        << " |\n";
  }
}

}  // namespace

Result<SatCheckSummary> ParseSatCheckJson(std::string_view text, std::string_view source) {
  const JsonValue root = JsonValue::parse(text, nullptr, false);
  if (root.is_discarded()) return Error{Concat({source, ": not valid JSON"})};
  JsonChecker check;
  SatCheckSummary s;
  if (const JsonValue* settings = check.Member(root, "$", "settings")) {
    s.pairs = check.Count(*settings, "$.settings", "pairs");
    s.seed = check.Integer(*settings, "$.settings", "seed", false);
    s.touchingBand = check.Number(*settings, "$.settings", "touchingBand", true);
  }
  s.pairCount = check.Count(root, "$", "pairCount");
  s.placements = ReadCounts(check, root, "placements");
  s.alignments = ReadCounts(check, root, "alignments");
  if (const JsonValue* truth = check.Member(root, "$", "truth")) {
    s.truthIntersecting = check.Count(*truth, "$.truth", "intersecting");
    s.truthTouchingBand = check.Count(*truth, "$.truth", "touchingBand");
    s.qhullChecks = check.Count(*truth, "$.truth", "qhullChecks");
    s.qhullMismatches = check.Count(*truth, "$.truth", "qhullMismatches");
  }
  if (const JsonValue* methods = check.Array(root, "$", "methods")) {
    if (methods->empty()) check.Fail("$.methods", "at least one method");
    for (std::size_t i = 0; i < methods->size() && !check.Failed(); ++i) {
      s.methods.push_back(ReadMethod(check, (*methods)[i], Indexed("$", "methods", i)));
    }
  }
  for (std::size_t i = 0; i < s.methods.size() && !check.Failed(); ++i) {
    const SatMethod& m = s.methods[i];
    if (static_cast<long long>(m.agree) + m.disagree + m.oracleFailures > s.pairCount) {
      check.Fail(Indexed("$", "methods", i) + ".verdict", "agree + disagree + oracleFailures <= pairCount");
    }
  }
  if (check.Failed()) return Error{Concat({source, ": ", check.Message()})};
  return s;
}

Result<SatCheckSummary> ReadSatCheckFile(const std::filesystem::path& path) {
  auto text = ReadTextFile(path, "the sat-check results");
  if (!text) return text.GetError();
  return ParseSatCheckJson(text.Value(), path.string());
}

std::string SatCheckMarkdown(const SatCheckSummary& s) {
  std::ostringstream out;
  out << "## SAT validation\n\n";
  out << "From `talus-sat-check`: " << s.pairCount << " generated shape pairs (seed " << s.seed << "): ";
  for (std::size_t i = 0; i < s.placements.size(); ++i) {
    out << (i ? ", " : "") << s.placements[i].second << " " << s.placements[i].first;
  }
  out << "; alignments ";
  for (std::size_t i = 0; i < s.alignments.size(); ++i) {
    out << (i ? ", " : "") << s.alignments[i].second << " " << s.alignments[i].first;
  }
  out << ". The truth is exact (Minkowski difference): " << s.truthIntersecting << " intersecting, "
      << s.truthTouchingBand << " within the touching band (" << FormatPrintf("%.0e", s.touchingBand)
      << " m, either verdict accepted); Minkowski hull vs qhull: " << s.qhullMismatches << " mismatches in "
      << s.qhullChecks << ".\n\n";

  out << "### SAT validation: verdicts\n\n"
         "| method | family | agreement | wrong verdicts | in-band differences | oracle failures |\n"
         "|---|---|---|---|---|---|\n";
  for (const SatMethod& m : s.methods) {
    out << "| " << m.name << " | " << m.family << " | "
        << (s.pairCount == 0 ? std::string("-") : FormatPrintf("%.2f%%", 100.0 * m.agree / s.pairCount))
        << " | " << m.disagree << " | " << m.touchingBandDisagree << " | " << m.oracleFailures << " |\n";
  }

  out << "\n### SAT validation: error distributions and time\n\n"
         "p50 / p90 / p99 / max over the pairs where the measure applies. Depth error |d - d*| (m) over "
         "pairs both call intersecting, outside the band; normal angle (rad) to the true normal where the "
         "minimum is unique; normal excess (m): overlap along the reported normal minus the true depth.\n\n"
         "| method | depth error (m) | normal angle (rad) | normal excess (m) | time per query p50 (ns) |\n"
         "|---|---|---|---|---|\n";
  for (const SatMethod& m : s.methods) {
    out << "| " << m.name << " | " << Percentiles(m.depthError) << " | " << Percentiles(m.normalAngle)
        << " | " << Percentiles(m.normalExcess) << " | "
        << (m.timeNs.count ? FormatPrintf("%.0f", m.timeNs.p50) : std::string("-")) << " |\n";
  }

  out << "\n### SAT validation: worst cases\n\n"
         "Per method: every wrong verdict outside the band (at most 5 listed), then the "
      << kWorstListed
      << " largest depth errors and normal angles. Distances in m (negative: penetrating), angles in "
         "rad.\n\n"
         "| method | kind | pair | configuration | true signed distance | method says intersecting | error "
         "|\n"
         "|---|---|---|---|---|---|---|\n";
  for (const SatMethod& m : s.methods) {
    WorstRows(out, m, "wrong verdict", m.disagreements, 5, "");
    WorstRows(out, m, "depth", m.worstDepth, kWorstListed, "m");
    WorstRows(out, m, "normal", m.worstNormal, kWorstListed, "rad");
  }
  return out.str();
}

}  // namespace talus::harness
