// `talus hull`: read points, build the hull with Quickhull, compute mass
// properties, format, write. Each stage returns a Result so that the first
// error stops the run before anything is written.
#include "hull_command.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string_view>

#include "flag_range.h"
#include "point_file.h"
#include "talus/hull_builder.h"
#include "talus/mass_properties.h"

namespace talus::cli {
namespace {

// Shortest text that reads back to the same double (std::to_chars), so OBJ
// output round-trips exactly and does not depend on the locale.
std::string FormatNumber(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

// Appends each piece in turn (GCC 12 mis-warns -Wrestrict on chains of
// std::string operator+ with literals).
void Append(std::string& text, std::initializer_list<std::string_view> pieces) {
  for (std::string_view piece : pieces) text.append(piece);
}

std::string FormatObj(const Hull& hull, const std::string& source) {
  std::string text;
  Append(text, {"# talus hull of ", source, ": ", std::to_string(hull.VertexCount()), " vertices, ",
                std::to_string(hull.FaceCount()), " faces\n"});
  for (const Vec3& v : hull.Vertices()) {
    Append(text, {"v ", FormatNumber(v.x()), " ", FormatNumber(v.y()), " ", FormatNumber(v.z()), "\n"});
  }
  for (int f = 0; f < hull.FaceCount(); ++f) {
    text.append("f");
    for (int v : hull.FaceVertices(f)) Append(text, {" ", std::to_string(v + 1)});
    text.append("\n");
  }
  return text;
}

std::string FormatJson(const Hull& hull, const MassProperties& props, double density) {
  nlohmann::ordered_json json;
  json["vertices"] = nlohmann::json::array();
  for (const Vec3& v : hull.Vertices()) json["vertices"].push_back({v.x(), v.y(), v.z()});
  json["faces"] = nlohmann::json::array();
  for (int f = 0; f < hull.FaceCount(); ++f) json["faces"].push_back(hull.FaceVertices(f));
  json["volume"] = props.volume;
  json["density"] = density;
  json["mass"] = props.mass;
  const Vec3& c = props.centerOfMass;
  json["centerOfMass"] = {c.x(), c.y(), c.z()};
  json["inertia"] = nlohmann::json::array();
  for (int row = 0; row < 3; ++row) {
    json["inertia"].push_back({props.inertia(row, 0), props.inertia(row, 1), props.inertia(row, 2)});
  }
  return json.dump() + "\n";  // one line: compact and easy to diff
}

// Writes `text` to `path` via a temporary sibling renamed into place, so the
// file either holds the complete output or is left as it was. The sibling's
// name carries the process id and a per-process count (TemporarySibling),
// so two programs writing the same output at once never share one
// temporary file: each renames its own complete text into place.
Result<bool> WriteWhole(const std::string& path, const std::string& text) {
  const std::string temporary = TemporarySibling(path);
  const auto reason = [](const char* otherwise) { return errno != 0 ? std::strerror(errno) : otherwise; };
  {
    errno = 0;
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    if (!file)
      return Error{path + ": cannot open for writing (" + reason("cannot create a file there") + ")"};
    file << text;
    file.close();  // flushes: a full disk shows here
    if (!file) {
      const std::string why = reason("write failed");
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      return Error{path + ": cannot write (" + why + ")"};
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    return Error{path + ": cannot replace file (" + error.message() + ")"};
  }
  return true;
}

}  // namespace

std::string TemporarySibling(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  return path + ".tmp-" + std::to_string(static_cast<long long>(::getpid())) + "-" +
         std::to_string(counter++);
}

namespace {

// Everything up to the output text; the first failure is the result.
Result<std::string> MakeOutput(const HullOptions& options) {
  if (options.maxVertices != 0 && options.maxVertices < 4) {
    return Error{"--max-vertices must be 0 (no cap) or at least 4, got " +
                 std::to_string(options.maxVertices)};
  }
  if (!std::isfinite(options.density) || !(options.density > 0.0)) {
    return Error{"--density must be finite and > 0 kg/m^3, got " + FormatNumber(options.density)};
  }
  auto format = ParsePointFormat(options.inputFormat);
  if (!format) return format.GetError();
  auto points = ReadPointFile(options.input, format.Value());
  if (!points) return points.GetError();
  auto hull = BuildHull(points.Value(), {.maxVertices = options.maxVertices});
  if (!hull) return Error{options.input + ": no hull: " + hull.GetError().message};
  if (options.format == "obj") return FormatObj(hull.Value(), options.input);
  auto props = ComputeMassProperties(hull.Value(), options.density);
  if (!props) return Error{options.input + ": no mass properties: " + props.GetError().message};
  return FormatJson(hull.Value(), props.Value(), options.density);
}

}  // namespace

void AddHullCommand(CLI::App& app, HullOptions& options, int& exitCode) {
  CLI::App* hull = app.add_subcommand("hull", "Print the convex hull of a point file as OBJ or JSON");
  hull->add_option("FILE", options.input, "Point file: 'x y z' lines or OBJ 'v x y z' lines")->required();
  hull->add_option("-o,--output", options.output, "Write to this file instead of stdout");
  hull->add_option("-f,--format", options.format, "Output format")
      ->check(CLI::IsMember({"obj", "json"}))
      ->capture_default_str();
  hull->add_option("--input-format", options.inputFormat,
                   "Point file format (auto: by extension and contents)")
      ->check(CLI::IsMember({"auto", "xyz", "obj"}))
      ->capture_default_str();
  // 1 to 3 fall inside the range but are refused by MakeOutput: no hull
  // has fewer than 4 vertices.
  hull->add_option("--max-vertices", options.maxVertices,
                   "Keep at most N hull vertices (0: no cap, else >= 4)")
      ->check(flags::InRange(0, std::numeric_limits<int>::max()))
      ->capture_default_str();
  hull->add_option("--density", options.density, "Density in kg/m^3 for the JSON mass figures")
      ->check(flags::InRange(0.0, std::numeric_limits<double>::max(), /*lowerOpen=*/true))
      ->capture_default_str();
  hull->callback([&options, &exitCode] { exitCode = RunHull(options); });
}

int RunHull(const HullOptions& options) {
  auto output = MakeOutput(options);
  if (!output) {
    std::cerr << "talus hull: " << output.GetError().message << "\n";
    return 1;
  }
  if (options.output.empty()) {
    // The flush shows a full disk or a closed stream; the text is not done
    // until it has been handed over whole.
    errno = 0;
    std::cout << output.Value();
    std::cout.flush();
    if (!std::cout) {
      std::cerr << "talus hull: stdout: cannot write ("
                << (errno != 0 ? std::strerror(errno) : "write failed") << ")\n";
      return 1;
    }
    return 0;
  }
  auto written = WriteWhole(options.output, output.Value());
  if (!written) {
    std::cerr << "talus hull: " << written.GetError().message << "\n";
    return 1;
  }
  return 0;
}

}  // namespace talus::cli
