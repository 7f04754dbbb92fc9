// `talus-testbed stress`: the stability envelope of each backend along the
// chosen stress axes (harness stress.h), written as stress.md, stress.json
// and stress.html. Defaults are CI-sized; --full uses the long searches.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

#include "sweep_commands.h"
#include "talus/harness/stress/stress.h"
#include "talus/reference/all_backends.h"
#include "testbed_commands.h"

namespace talus::testbed {
namespace {

namespace fs = std::filesystem;

struct StressOptions {
  std::vector<std::string> backends{"talus", "bullet", "ode-step", "ode-quickstep", "mujoco", "mujoco-tuned"};
  std::vector<std::string> axes;
  std::vector<std::string> limits;  ///< "axis=value"
  bool full = false;
  std::string out = "reports/stress";
  bool quiet = false;
};

int Stress(const StressOptions& options) {
  std::vector<harness::StressAxisInfo> chosen;
  for (const harness::StressAxisInfo& info : harness::StressAxes()) {
    if (options.axes.empty() ||
        std::find(options.axes.begin(), options.axes.end(), info.name) != options.axes.end())
      chosen.push_back(info);
  }
  for (const std::string& name : options.axes) {
    if (std::none_of(chosen.begin(), chosen.end(), [&](const auto& info) { return info.name == name; })) {
      std::cerr << "talus-testbed: unknown stress axis \"" << name << "\"\n";
      return kExitBadInput;
    }
  }
  std::map<std::string, double> limits;
  for (const std::string& text : options.limits) {
    const auto equals = text.find('=');
    const std::string name = text.substr(0, equals);
    char* end = nullptr;
    const double limit = equals == std::string::npos ? 0.0 : std::strtod(text.c_str() + equals + 1, &end);
    if (std::none_of(harness::StressAxes().begin(), harness::StressAxes().end(),
                     [&](const auto& info) { return info.name == name; }) ||
        end == nullptr || *end != '\0' || !std::isfinite(limit) || !(limit > 0.0)) {
      std::cerr << "talus-testbed: --limit " << text
                << ": expected AXIS=VALUE with a known axis and VALUE > 0\n";
      return kExitBadInput;
    }
    limits[name] = limit;
  }
  for (const std::string& backend : options.backends) {
    if (!reference::AllBackends().Has(backend)) {
      std::cerr << "talus-testbed: unknown backend \"" << backend << "\"\n";
      return kExitBadInput;
    }
  }
  std::vector<harness::StressEntry> entries;
  for (const harness::StressAxisInfo& info : chosen) {
    harness::EnvelopeSearch search = options.full ? info.full : info.ci;
    if (auto it = limits.find(info.name); it != limits.end()) search.limit = it->second;
    for (const std::string& backend : options.backends) {
      const auto start = std::chrono::steady_clock::now();
      harness::StressEntry entry{info.name, backend, {}};
      entry.envelope = harness::SearchEnvelope(search, [&](double value) {
        harness::EnvelopeProbe probe =
            harness::ProbeStress(reference::AllBackends(), backend, info.axis, value);
        if (!options.quiet) {
          std::fprintf(stderr, "[stress] %s %s %.4g: %s%s%s\n", info.name.c_str(), backend.c_str(), value,
                       probe.pass ? "ok" : "FAIL", probe.detail.empty() ? "" : " - ", probe.detail.c_str());
        }
        return probe;
      });
      if (!options.quiet) {
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::fprintf(stderr, "[stress] %s %s done in %.1f s\n", info.name.c_str(), backend.c_str(), seconds);
      }
      entries.push_back(std::move(entry));
    }
  }
  const std::string markdown = harness::StressMarkdown(entries);
  const fs::path out(options.out);
  if (!WriteTexts({{out / "stress.md", markdown},
                   {out / "stress.json", harness::StressJson(entries)},
                   {out / "stress.html", harness::StressHtml(entries)}})) {
    return kExitBadInput;
  }
  std::cout << markdown << "\nstress: " << (fs::path(options.out) / "stress.html").string() << "\n";
  return kExitOk;
}

}  // namespace

void AddStressCommand(CLI::App& app, CommandAction& chosen) {
  auto options = std::make_shared<StressOptions>();
  CLI::App* command = app.add_subcommand("stress", "stability envelope per engine along stress axes");
  command->add_option("-b,--backend", options->backends, "backends")->delimiter(',')->capture_default_str();
  command
      ->add_option("--axis", options->axes,
                   "axes: column, mass-ratio, time-step, offset, speed, energy-drift, small-size, large-size "
                   "(default: all)")
      ->delimiter(',');
  command->add_option("--limit", options->limits, "override an axis's search limit, e.g. --limit column=64");
  command->add_flag("--full", options->full, "the long searches (default: CI-sized)");
  command->add_option("-o,--out", options->out, "output folder")->capture_default_str();
  command->add_flag("-q,--quiet", options->quiet, "no progress on stderr");
  command->callback([options, &chosen] { chosen = [options] { return Stress(*options); }; });
}

}  // namespace talus::testbed
