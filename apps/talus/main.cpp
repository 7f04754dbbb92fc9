// The `talus` command line: one CLI11 app, one file per subcommand
// (hull_command.cpp, ...). main only wires them together and returns the
// exit status of the subcommand that ran.
#include <CLI/CLI.hpp>

#include "hull_command.h"

int main(int argc, char** argv) {
  CLI::App app{"talus: convex hulls, mass properties and the physics testbed"};
  app.require_subcommand(1);
  int exitCode = 0;
  talus::cli::HullOptions hullOptions;
  talus::cli::AddHullCommand(app, hullOptions, exitCode);
  CLI11_PARSE(app, argc, argv);
  return exitCode;
}
