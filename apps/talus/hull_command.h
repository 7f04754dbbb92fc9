// `talus hull FILE`: the convex hull of a point file, printed as OBJ or as
// JSON with its mass properties.
//
// The command reads and validates everything, builds the whole output text
// in memory, and only then writes it: to stdout, or to --output through a
// temporary file renamed into place, so a failed run never leaves a
// half-written output file.
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace talus::cli {

/// Options of `talus hull`, filled by CLI11.
struct HullOptions {
  std::string input;                 ///< point file to read (required)
  std::string output;                ///< file to write; empty = stdout
  std::string format = "obj";        ///< "obj" or "json"
  std::string inputFormat = "auto";  ///< "auto", "xyz" or "obj"
  int maxVertices = 0;               ///< hull vertex cap; 0 = none, else >= 4
  double density = 1000.0;           ///< kg/m^3 for the JSON mass figures; finite, > 0
};

/// Registers the `hull` subcommand on `app`; parsed values go to `options`.
/// When the subcommand runs, its exit status is stored in `exitCode`.
void AddHullCommand(CLI::App& app, HullOptions& options, int& exitCode);

/// The temporary name `talus hull -o PATH` writes before renaming it over
/// PATH: "PATH.tmp-<process id>-<count>", unique per process and call, so
/// two runs writing one output at once never share a temporary file.
std::string TemporarySibling(const std::string& path);

/// Runs `talus hull` with `options`: 0 on success; 1 after printing an
/// error ("points.xyz:7: expected 3 numbers, got 2") to stderr.
int RunHull(const HullOptions& options);

}  // namespace talus::cli
