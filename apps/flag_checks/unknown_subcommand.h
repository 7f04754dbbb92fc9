// The first word of a command line, when it is not a flag and names no
// subcommand of `app`: CLI11 alone would answer "A subcommand is required"
// or "was not expected" without naming it. Shared by every program with
// subcommands.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace talus::cli {

/// "unknown subcommand "frobnicate" (known: hull)" when argv[1] is neither a
/// flag nor one of app's subcommands; nothing otherwise.
inline std::optional<std::string> UnknownSubcommand(CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return std::nullopt;
  std::string known;
  for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    if (command->get_name() == argv[1]) return std::nullopt;
    known.append(known.empty() ? "" : ", ").append(command->get_name());
  }
  return "unknown subcommand \"" + std::string(argv[1]) + "\" (known: " + known + ")";
}

}  // namespace talus::cli
