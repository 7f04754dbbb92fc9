// CSV and JSON-lines formatting of benchmark reports (see report_writer.h).
#include "report_writer.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

namespace talus::scenes {
namespace {

// Six significant digits: enough for milliseconds and millimetres, short
// enough to read in a terminal.
std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

std::string Optional(const std::optional<double>& value) { return value ? Number(*value) : std::string(); }

// CSV quoting (RFC 4180): double quotes around, inner quotes doubled.
std::string Quote(const std::string& text) {
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

nlohmann::ordered_json JsonNumber(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

}  // namespace

std::string CsvHeader() {
  return "engine,scene,parameter,bodies,threads,steps,ms_per_step_median,ms_per_step_mean,max_contacts,"
         "drift_m,max_penetration_m,kinetic_energy_j,escaped,skipped";
}

std::string FormatCsv(const harness::BenchReport& report) {
  std::string line = report.engine + "," + report.scene + "," + std::to_string(report.parameter) + "," +
                     std::to_string(report.bodies) + "," + std::to_string(report.threads) + "," +
                     std::to_string(report.steps) + ",";
  if (!report.skipped.empty()) return line + ",,,,,,," + Quote(report.skipped);
  line += Number(report.msMedian) + "," + Number(report.msMean) + "," + std::to_string(report.maxContacts) +
          "," + Optional(report.drift) + "," + Optional(report.maxPenetration) + "," +
          Optional(report.kineticEnergy) + "," + (report.escaped ? std::to_string(*report.escaped) : "") +
          ",";
  return line;
}

std::string FormatJson(const harness::BenchReport& report) {
  nlohmann::ordered_json line;
  line["engine"] = report.engine;
  line["scene"] = report.scene;
  line["parameter"] = report.parameter;
  line["bodies"] = report.bodies;
  line["threads"] = report.threads;
  line["steps"] = report.steps;
  if (!report.skipped.empty()) {
    line["skipped"] = report.skipped;
    return line.dump();
  }
  line["ms_per_step_median"] = JsonNumber(report.msMedian);
  line["ms_per_step_mean"] = JsonNumber(report.msMean);
  line["max_contacts"] = report.maxContacts;
  if (report.drift) line["drift_m"] = JsonNumber(*report.drift);
  if (report.maxPenetration) line["max_penetration_m"] = JsonNumber(*report.maxPenetration);
  if (report.kineticEnergy) line["kinetic_energy_j"] = JsonNumber(*report.kineticEnergy);
  if (report.escaped) line["escaped"] = *report.escaped;
  return line.dump();
}

}  // namespace talus::scenes
