// The peers' configurations in the report (report_peers.h).
#include "report/report_peers.h"

#include <sstream>

#include "support/text_util.h"

namespace talus::harness {
namespace {

constexpr std::string_view kTunedSuffix = "-tuned";

// Table cells may not hold a pipe or a line break.
std::string CellText(const std::string& text) {
  std::string cell;
  for (char c : text) cell += c == '|' ? '/' : c == '\n' ? ' ' : c;
  return cell;
}

}  // namespace

std::string TunedName(const std::string& backend) {
  if (backend.ends_with(kTunedSuffix)) return "";
  return backend + std::string(kTunedSuffix);
}

std::string DeparturesTable(const std::vector<Setting>& settings) {
  std::ostringstream out;
  for (const Setting& s : settings) {
    if (s.engineDefault.empty()) continue;
    if (out.tellp() == 0) {
      out << "| setting | value here | engine default | why, and its measured effect |\n|---|---|---|---|\n";
    }
    out << "| " << CellText(s.key) << " | " << CellText(s.value) << " | " << CellText(s.engineDefault)
        << " | " << CellText(s.effect) << " |\n";
  }
  return out.str();
}

}  // namespace talus::harness
