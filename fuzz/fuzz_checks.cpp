// The fuzz targets' invariants (see fuzz_checks.h).
#include "fuzz_checks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <set>
#include <string_view>

#include "point_file.h"
#include "talus/hull.h"
#include "talus/hull_builder.h"

namespace talus::fuzz {
namespace {

// At most this many points per input: enough for every degenerate shape,
// small enough that libFuzzer runs thousands of inputs a second.
constexpr std::size_t kMaxPoints = 512;

// Longest error message the point reader may produce (bytes): the file name
// (at most 16 here), the line number, a fixed text and two quoted token
// prefixes of 40 bytes, each byte escaped to at most 4 characters.
constexpr std::size_t kMaxMessage = 512;

}  // namespace

std::vector<Vec3> DecodeHullInput(std::span<const std::uint8_t> data) {
  std::vector<Vec3> points;
  if (data.empty()) return points;
  const int mode = data[0] % 5;
  const double scale = data.size() > 1 ? std::ldexp(1.0, -(data[1] % 64)) : 1.0;
  const std::size_t start = mode == 0 || mode == 4 ? 1 : 2;
  std::vector<double> values;
  for (std::size_t at = start; at + sizeof(double) <= data.size(); at += sizeof(double)) {
    double value = 0.0;
    std::memcpy(&value, data.data() + at, sizeof(double));
    values.push_back(value);
  }
  for (std::size_t i = 0; i + 2 < values.size() && points.size() < kMaxPoints; i += 3) {
    const Vec3 raw(values[i], values[i + 1], values[i + 2]);
    const Vec3 unit(Fraction(raw.x()), Fraction(raw.y()), Fraction(raw.z()));
    switch (mode) {
      case 1: {
        // The centre is the first point's raw value when finite.
        if (points.empty()) {
          points.push_back(raw.allFinite() ? raw : Vec3::Zero());
        } else {
          points.push_back(points.front() + scale * unit);
        }
        break;
      }
      case 2:
        points.emplace_back(unit.x(), scale * unit.y(), scale * unit.z());
        break;
      case 3:
        points.emplace_back(unit.x(), unit.y(), scale * unit.z());
        break;
      case 4:
        for (int copy = 0; copy < 3; ++copy) points.push_back(raw);
        break;
      default:
        points.push_back(raw);
        break;
    }
  }
  return points;
}

std::string CheckHullBuild(std::span<const Vec3> points) {
  const bool finite = std::all_of(points.begin(), points.end(), [](const Vec3& p) { return p.allFinite(); });
  auto built = BuildHull(points);
  if (!built) {
    const std::string& message = built.GetError().message;
    if (message.empty()) return "error without a message";
    if (message.find("please keep this point set") != std::string::npos) return "builder gave up: " + message;
    return {};
  }
  if (!finite) return "a hull was built from NaN or infinite coordinates";
  const Hull& hull = built.Value();
  const double tolerance = hull.Tolerance();
  // Vertices are input points, bit for bit.
  std::set<std::array<double, 3>> inputs;
  for (const Vec3& p : points) inputs.insert({p.x(), p.y(), p.z()});
  for (const Vec3& v : hull.Vertices()) {
    if (!inputs.contains({v.x(), v.y(), v.z()})) return "a hull vertex is not an input point";
  }
  // Closed and Euler-consistent.
  if (hull.VertexCount() - hull.EdgeCount() + hull.FaceCount() != 2) return "V - E + F is not 2";
  for (int h = 0; h < hull.HalfEdgeCount(); ++h) {
    const HullHalfEdge& edge = hull.HalfEdges()[static_cast<std::size_t>(h)];
    if (hull.HalfEdges()[static_cast<std::size_t>(edge.twin)].twin != h) return "twins are not mutual";
  }
  // Convex, holding every input point (vertices included) within tolerance.
  for (int f = 0; f < hull.FaceCount(); ++f) {
    const Plane& plane = hull.Faces()[static_cast<std::size_t>(f)].plane;
    for (const Vec3& p : points) {
      if (plane.SignedDistance(p) > tolerance) {
        return "an input point is " + std::to_string(plane.SignedDistance(p)) + " m in front of face " +
               std::to_string(f) + " (tolerance " + std::to_string(tolerance) + " m)";
      }
    }
  }
  return {};
}

std::string CheckPointFileParse(std::string_view text) {
  static constexpr std::array<cli::PointFormat, 3> kFormats = {cli::PointFormat::Xyz, cli::PointFormat::Obj,
                                                               cli::PointFormat::Auto};
  for (cli::PointFormat format : kFormats) {
    auto points = cli::ParsePoints(text, "fuzz.txt", format);
    if (points) {
      if (points.Value().empty()) return "success without points";
      for (const Vec3& p : points.Value()) {
        if (!p.allFinite()) return "a non-finite point was accepted";
      }
      continue;
    }
    const std::string& message = points.GetError().message;
    if (!message.starts_with("fuzz.txt")) return "error does not name the file: " + message.substr(0, 80);
    if (message.size() > kMaxMessage) return "error of " + std::to_string(message.size()) + " bytes";
    for (char c : message) {
      const auto byte = static_cast<unsigned char>(c);
      if (byte < 0x20 || byte >= 0x7f) return "error holds a non-printable byte";
    }
  }
  return {};
}

}  // namespace talus::fuzz
