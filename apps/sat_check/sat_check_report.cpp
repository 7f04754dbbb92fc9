// The report as JSON (every number, for the comparison report and for
// plots) and as a Markdown section (the headline tables). The JSON layout
// is documented in docs/collision-validation.md.
#include <nlohmann/json.hpp>

#include <cstdio>
#include <ostream>
#include <sstream>

#include "sat_check.h"
#include "talus/harness/support/number_text.h"

namespace talus::validation {
namespace {

using Json = nlohmann::ordered_json;

Json ToJson(const Distribution& d) {
  return {{"count", d.count}, {"p50", d.p50}, {"p90", d.p90}, {"p99", d.p99}, {"max", d.max}};
}

Json ToJson(const std::vector<CaseRecord>& cases) {
  Json out = Json::array();
  for (const CaseRecord& c : cases) {
    out.push_back({{"pair", c.pair},
                   {"configuration", c.configuration},
                   {"trueSignedDistance", c.trueSignedDistance},
                   {"methodIntersecting", c.methodIntersecting},
                   {"value", c.value}});
  }
  return out;
}

Json FamiliesToJson(const std::vector<FamilyReport>& families) {
  Json out = Json::array();
  for (const FamilyReport& f : families) {
    out.push_back({{"family", f.family},
                   {"depthError", ToJson(f.depthError)},
                   {"normalAngle", ToJson(f.normalAngle)},
                   {"normalExcess", ToJson(f.normalExcess)},
                   {"pointOutside", ToJson(f.pointOutside)}});
  }
  return out;
}

std::string Percent(int part, int whole) {
  return whole == 0 ? "-" : harness::FormatPrintf("%.2f%%", 100.0 * part / whole);
}

// The run's settings, the pair counts and the truth's own checks.
void AddRunToJson(const SatCheckReport& report, Json& json) {
  const SatCheckSettings& s = report.settings;
  json["settings"] = {{"pairs", s.pairs},
                      {"seed", s.seed},
                      {"touchingBand", s.touchingBand},
                      {"pointTolerance", s.pointTolerance},
                      {"timingRepeats", s.timingRepeats},
                      {"checkWithQhull", s.checkWithQhull}};
  json["pairCount"] = report.pairCount;
  Json placements;
  for (std::size_t i = 0; i < report.placementCounts.size(); ++i)
    placements[ToString(static_cast<Placement>(i))] = report.placementCounts[i];
  json["placements"] = placements;
  Json alignments;
  for (std::size_t i = 0; i < report.alignmentCounts.size(); ++i)
    alignments[ToString(static_cast<Alignment>(i))] = report.alignmentCounts[i];
  json["alignments"] = alignments;
  const TruthReport& t = report.truth;
  json["truth"] = {{"intersecting", t.intersecting},
                   {"touchingBand", t.touchingBand},
                   {"tiedMinimum", t.tiedMinimum},
                   {"qhullChecks", t.qhullChecks},
                   {"qhullMismatches", t.qhullMismatches},
                   {"qhullMessages", t.qhullMessages},
                   {"boxClosedFormChecks", t.boxClosedFormChecks},
                   {"boxClosedFormMaxError", t.boxClosedFormMaxError},
                   {"boxClosedFormVerdictMismatches", t.boxClosedFormVerdictMismatches}};
}

Json MethodToJson(const MethodReport& m) {
  return {{"name", m.name},
          {"family", m.family},
          {"givesDepth", m.givesDepth},
          {"givesPoints", m.givesPoints},
          {"verdict",
           {{"agree", m.agree},
            {"disagree", m.disagree},
            {"touchingBandDisagree", m.touchingBandDisagree},
            {"oracleFailures", m.oracleFailures}}},
          {"disagreements", ToJson(m.disagreements)},
          {"depthError", ToJson(m.depthError)},
          {"normalAngle", ToJson(m.normalAngle)},
          {"normalExcess", ToJson(m.normalExcess)},
          {"pointOutside", ToJson(m.pointOutside)},
          {"pointsOverTolerance", m.pointsOverTolerance},
          {"gate",
           {{"depthOverBound", m.depthOverBound},
            {"normalOverBound", m.normalOverBound},
            {"deepestPointDeeper", m.deepestPointDeeper},
            {"pointsOutsideEither", m.pointsOutsideEither},
            {"pointsOutsideBoth", m.pointsOutsideBoth}}},
          {"deepestPointShallower", m.deepestPointShallower},
          {"families", FamiliesToJson(m.families)},
          {"timeNs", ToJson(m.timeNs)},
          {"timeVsAccuracy",
           {{"medianTimeNs", m.timeNs.p50},
            {"medianDepthError", m.depthError.p50},
            {"medianNormalAngle", m.normalAngle.p50},
            {"medianNormalExcess", m.normalExcess.p50}}},
          {"worstDepth", ToJson(m.worstDepth)},
          {"worstNormal", ToJson(m.worstNormal)}};
}

// One row per pair: its truth and each method's answer, in the fields of
// pairResultFields.
Json PairsToJson(const std::vector<PairRecord>& records) {
  Json pairs = Json::array();
  for (const PairRecord& p : records) {
    Json results = Json::array();
    for (const PairMethodResult& r : p.results) {
      results.push_back({r.ok, r.intersecting, r.depth, r.normalExcess, r.points, r.timeNs});
    }
    pairs.push_back({{"index", p.index},
                     {"configuration", p.configuration},
                     {"trueSignedDistance", p.trueSignedDistance},
                     {"trueNormal", {p.trueNormal.x(), p.trueNormal.y(), p.trueNormal.z()}},
                     {"results", results}});
  }
  return pairs;
}

// The heading, the pairs made and the checks of the truth.
void WriteOverview(const SatCheckReport& report, std::ostream& out) {
  const TruthReport& t = report.truth;
  out << "## SAT validation\n\n";
  out << report.pairCount << " pairs (seed " << report.settings.seed << "): ";
  for (std::size_t i = 0; i < report.placementCounts.size(); ++i)
    out << (i ? ", " : "") << report.placementCounts[i] << " " << ToString(static_cast<Placement>(i));
  out << "; ";
  for (std::size_t i = 0; i < report.alignmentCounts.size(); ++i)
    out << (i ? ", " : "") << report.alignmentCounts[i] << " " << ToString(static_cast<Alignment>(i));
  out << ". Truth: " << t.intersecting << " intersecting, " << t.touchingBand << " within the touching band ("
      << harness::FormatPrintf("%.0e", report.settings.touchingBand) << " m), " << t.tiedMinimum
      << " with a tied minimum direction; Minkowski hull vs qhull: " << t.qhullMismatches << " mismatches in "
      << t.qhullChecks << "; face-aligned boxes vs closed form: " << t.boxClosedFormChecks
      << " checked, max error " << harness::FormatPrintf("%.2e", t.boxClosedFormMaxError) << " m, "
      << t.boxClosedFormVerdictMismatches << " verdict mismatches.\n\n";
}

void WriteVerdicts(const SatCheckReport& report, std::ostream& out) {
  out << "### Verdicts\n\n| method | agree | disagree | in band | oracle failures |\n|---|---|---|---|---|\n";
  for (const MethodReport& m : report.methods) {
    out << "| " << m.name << " | " << Percent(m.agree, report.pairCount) << " | " << m.disagree << " | "
        << m.touchingBandDisagree << " | " << m.oracleFailures << " |\n";
  }
}

// Depth, normal and contact points against the truth, with the time.
void WriteAccuracy(const SatCheckReport& report, std::ostream& out) {
  out << "\n### Depth, normal and contact points against the truth\n\n"
         "Depth error |d - d*| (m), normal angle (rad, pairs with a unique minimum), normal excess (overlap "
         "along "
         "the reported normal minus the true depth, m), contact points outside either shape (m); p50 / p99 / "
         "max. Points > tol: points farther out of either shape than the true depth + "
      << harness::FormatPrintf("%.0e", report.settings.pointTolerance)
      << " m.\n\n"
         "| method | depth error | normal angle | normal excess | point outside | points > tol | time p50 "
         "(ns) |\n"
         "|---|---|---|---|---|---|---|\n";
  const auto triple = [](const Distribution& d) {
    if (d.count == 0) return std::string("-");
    return harness::FormatPrintf("%.1e", d.p50) + " / " + harness::FormatPrintf("%.1e", d.p99) + " / " +
           harness::FormatPrintf("%.1e", d.max);
  };
  for (const MethodReport& m : report.methods) {
    out << "| " << m.name << " | " << triple(m.depthError) << " | " << triple(m.normalAngle) << " | "
        << triple(m.normalExcess) << " | " << triple(m.pointOutside) << " | " << m.pointsOverTolerance
        << " | " << (m.timeNs.count ? harness::FormatPrintf("%.0f", m.timeNs.p50) : std::string("-"))
        << " |\n";
  }
}

void WriteFamilies(const SatCheckReport& report, std::ostream& out) {
  out << "\n### By family (Talus modes)\n\n"
         "Depth error and normal excess (m), p50 / max, per family of pairs (pair_generator.h).\n\n"
         "| method | family | depth error | normal excess | point outside |\n|---|---|---|---|---|\n";
  const auto pair = [](const Distribution& d) {
    if (d.count == 0) return std::string("-");
    return harness::FormatPrintf("%.1e", d.p50) + " / " + harness::FormatPrintf("%.1e", d.max);
  };
  for (const MethodReport& m : report.methods) {
    if (m.family != "talus") continue;
    for (const FamilyReport& f : m.families) {
      out << "| " << m.name << " | " << f.family << " | " << pair(f.depthError) << " | "
          << pair(f.normalExcess) << " | " << pair(f.pointOutside) << " |\n";
    }
  }
}

void WriteGate(const SatCheckReport& report, std::ostream& out) {
  out << "\n### Gate\n\n" << SummaryLine(report) << "\n";
  for (const std::string& line : report.truthBroken) out << "- truth broken: " << line << "\n";
  for (const std::string& line : report.failures) out << "- " << line << "\n";
  out << "\nMeasured, not gated: manifolds whose deepest point is shallower than the depth (the SAT's "
         "deepest vertex outside the other shape, so no point of the intersection is that deep):";
  for (const MethodReport& m : report.methods) {
    if (m.family == "talus") out << " " << m.name << " " << m.deepestPointShallower << ";";
  }
}

void WriteWorstCases(const SatCheckReport& report, std::ostream& out) {
  out << "\n\n### Worst cases\n\n";
  for (const MethodReport& m : report.methods) {
    if (m.disagreements.empty() && (m.worstDepth.empty() || m.worstDepth.front().value < 1e-6)) continue;
    out << "- **" << m.name << "**";
    if (!m.disagreements.empty()) {
      out << ": wrong verdicts (the truth is right) on " << m.disagreements.size() << " pairs, e.g. pair "
          << m.disagreements.front().pair << " (" << m.disagreements.front().configuration
          << ", true distance " << harness::FormatPrintf("%.3e", m.disagreements.front().trueSignedDistance)
          << " m)";
    }
    if (!m.worstDepth.empty() && m.worstDepth.front().value >= 1e-6) {
      out << "; worst depth error " << harness::FormatPrintf("%.3e", m.worstDepth.front().value)
          << " m on pair " << m.worstDepth.front().pair << " (" << m.worstDepth.front().configuration << ")";
    }
    out << "\n";
  }
}

}  // namespace

std::string ReportToJson(const SatCheckReport& report) {
  Json json;
  AddRunToJson(report, json);
  Json methods = Json::array();
  for (const MethodReport& m : report.methods) methods.push_back(MethodToJson(m));
  json["methods"] = methods;
  json["failures"] = report.failures;
  json["truthBroken"] = report.truthBroken;
  json["passed"] = ExitStatus(report) == kExitPassed;
  json["pairResultFields"] = {"ok", "intersecting", "depth", "normalExcess", "points", "timeNs"};
  json["pairs"] = PairsToJson(report.pairs);
  return json.dump(2) + "\n";
}

std::string ReportToMarkdown(const SatCheckReport& report) {
  std::ostringstream out;
  WriteOverview(report, out);
  WriteVerdicts(report, out);
  WriteAccuracy(report, out);
  WriteFamilies(report, out);
  WriteGate(report, out);
  WriteWorstCases(report, out);
  return out.str();
}

std::string SummaryLine(const SatCheckReport& report) {
  int talusMethods = 0;
  for (const MethodReport& m : report.methods) talusMethods += m.family == "talus" ? 1 : 0;
  std::ostringstream out;
  if (!report.truthBroken.empty()) {
    out << "TRUTH BROKEN: " << report.truthBroken.size() << " checks of the truth failed on "
        << report.pairCount << " pairs, so no verdict on Talus; first: " << report.truthBroken.front();
    return out.str();
  }
  if (report.failures.empty()) {
    out << "PASS: " << talusMethods << " Talus modes on " << report.pairCount
        << " pairs: verdicts, depths, normals and contact points within the stated bounds";
    return out.str();
  }
  out << "FAIL: " << report.failures.size() << " bounds broken by Talus modes on " << report.pairCount
      << " pairs; first: " << report.failures.front();
  return out.str();
}

}  // namespace talus::validation
