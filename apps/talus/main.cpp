// The `talus` command line: one CLI11 app, one file per subcommand
// (hull_command.cpp, ...). main only wires them together and returns the
// exit status of the subcommand that ran.
#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

#include "hull_command.h"
#include "unknown_subcommand.h"

int main(int argc, char** argv) {
  CLI::App app{"talus: convex hulls, mass properties and the physics testbed"};
  app.require_subcommand(1);
  int exitCode = 0;
  talus::cli::HullOptions hullOptions;
  talus::cli::AddHullCommand(app, hullOptions, exitCode);
  // CLI11 would say "A subcommand is required" about `talus frobnicate
  // FILE`: name the word it did not know, and the known ones.
  if (const auto unknown = talus::cli::UnknownSubcommand(app, argc, argv)) {
    std::cerr << "talus: " << *unknown << "\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // --help exits 0; every refused argument exits 2, as an unknown subcommand does.
    return app.exit(error) == 0 ? 0 : 2;
  }
  return exitCode;
}
