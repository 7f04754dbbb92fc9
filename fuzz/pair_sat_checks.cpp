// The pair query against a brute-force SAT (see pair_sat_checks.h).
#include "pair_sat_checks.h"

#include "fuzz_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>

#include "talus/hull.h"
#include "talus/hull_builder.h"
#include "talus/pair_query.h"
#include "talus/shape.h"

namespace talus::fuzz {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// The SAT's preference band (engine/src/collision/sat.h,
// kAxisPreferenceRelative), restated: a face may be reported instead of a
// deeper-by-less-than-this axis, as a fraction of the pair's size.
constexpr double kPreferenceRelative = 1e-7;

// Edge pairs closer to parallel than this (sine of their angle) give no
// cross-product axis: its direction would be round-off. Such a pair's
// Minkowski face is a sliver whose neighbours' axes bound the same gap.
constexpr double kMinEdgeSine = 1e-9;

class ValueReader {
 public:
  explicit ValueReader(std::span<const std::uint8_t> data) : m_data(data) {}
  double Next() {
    double value = 0.0;
    if (m_at + sizeof(double) <= m_data.size()) std::memcpy(&value, m_data.data() + m_at, sizeof(double));
    m_at += sizeof(double);
    return Fraction(value);
  }
  Vec3 NextVec3() {
    const double x = Next(), y = Next();
    return {x, y, Next()};
  }

 private:
  std::span<const std::uint8_t> m_data;
  std::size_t m_at = 3;
};

Transform ReadPose(ValueReader& reader) {
  Transform pose;
  pose.position = 2.0 * reader.NextVec3();
  const double w = reader.Next(), x = reader.Next(), y = reader.Next(), z = reader.Next();
  const Quat q(w, x, y, z);
  pose.rotation = q.norm() > 1e-3 ? q.normalized() : Quat::Identity();
  return pose;
}

// A shape's world vertices, world edge directions, world face normals and
// validation tolerance: what the brute force projects.
struct WorldPolytope {
  std::vector<Vec3> vertices;
  std::vector<Vec3> edges;
  std::vector<Vec3> normals;
  double tolerance = 0.0;
};

WorldPolytope Place(const Hull& hull, const Transform& pose) {
  WorldPolytope out;
  for (const Vec3& v : hull.Vertices()) out.vertices.push_back(pose.Apply(v));
  for (int e = 0; e < hull.EdgeCount(); ++e) {
    const HullHalfEdge& half = hull.HalfEdges()[static_cast<std::size_t>(2 * e)];
    const HullHalfEdge& twin = hull.HalfEdges()[static_cast<std::size_t>(half.twin)];
    out.edges.push_back(pose.rotation * (hull.Vertices()[static_cast<std::size_t>(twin.origin)] -
                                         hull.Vertices()[static_cast<std::size_t>(half.origin)]));
  }
  for (const HullFace& face : hull.Faces()) out.normals.push_back(pose.rotation * face.plane.normal);
  out.tolerance = hull.Tolerance();
  return out;
}

// min and max of the vertices' projections on `axis`.
std::pair<double, double> Project(const std::vector<Vec3>& vertices, const Vec3& axis) {
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (const Vec3& v : vertices) {
    const double d = v.dot(axis);
    low = std::min(low, d);
    high = std::max(high, d);
  }
  return {low, high};
}

// The gap between the two projections on a unit axis (negative: overlap).
double Gap(const WorldPolytope& a, const WorldPolytope& b, const Vec3& axis) {
  const auto [lowA, highA] = Project(a.vertices, axis);
  const auto [lowB, highB] = Project(b.vertices, axis);
  return std::max(lowA - highB, lowB - highA);
}

struct BruteForce {
  double maxGap = -std::numeric_limits<double>::infinity();  ///< over every axis
  bool certainlySeparated = false;                           ///< some axis separates by more than its bound
  bool certainlyOverlapping = true;                          ///< every axis overlaps by more than its bound
};

// `reach`: the largest distance between a vertex of A and one of B, which
// turns an axis direction error into a gap error.
BruteForce Sat(const WorldPolytope& a, const WorldPolytope& b, double reach) {
  BruteForce out;
  // A projection is a dot product of coordinates of size `reach`: a few
  // ulps of it. The hull's own tolerance covers faces fitted to within it.
  const double roundOff = 16.0 * kEps * reach;
  const auto consider = [&](const Vec3& axis, double bound) {
    const double gap = Gap(a, b, axis);
    out.maxGap = std::max(out.maxGap, gap);
    if (gap > bound) out.certainlySeparated = true;
    if (gap >= -bound) out.certainlyOverlapping = false;
  };
  for (const Vec3& n : a.normals) consider(n, roundOff + a.tolerance + b.tolerance);
  for (const Vec3& n : b.normals) consider(n, roundOff + a.tolerance + b.tolerance);
  for (const Vec3& ea : a.edges) {
    for (const Vec3& eb : b.edges) {
      const Vec3 cross = ea.cross(eb);
      const double sine = cross.norm() / (ea.norm() * eb.norm());
      if (!(sine > kMinEdgeSine)) continue;
      // The normalised cross product's direction is good to ~eps / sine.
      consider(cross / cross.norm(), roundOff * (1.0 + 1.0 / sine) + a.tolerance + b.tolerance);
    }
  }
  return out;
}

// Half the diagonal of the vertices' bounding box about the hull's frame.
double HalfDiagonal(const Hull& hull) {
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 high = -low;
  for (const Vec3& v : hull.Vertices()) {
    low = low.cwiseMin(v);
    high = high.cwiseMax(v);
  }
  return 0.5 * (high - low).norm();
}

std::string Describe(const char* what, double value) {
  char text[40];
  std::snprintf(text, sizeof text, " %.17g", value);
  return what + std::string(text);
}

}  // namespace

PairInput DecodePairInput(std::span<const std::uint8_t> data) {
  PairInput input;
  const std::uint8_t flags = data.empty() ? 0 : data[0];
  input.satMode = (flags & 1) != 0 ? SatMode::Full : SatMode::GaussMapPruned;
  input.a.box = (flags & 2) != 0;
  input.b.box = (flags & 4) != 0;
  const int countA = 4 + (data.size() > 1 ? data[1] % 9 : 0);
  const int countB = 4 + (data.size() > 2 ? data[2] % 9 : 0);
  ValueReader reader(data);
  for (FuzzShape* shape : {&input.a, &input.b}) {
    if (shape->box) {
      // Half extents in [0.05, 1.05] m: a box is never degenerate.
      shape->halfExtents = reader.NextVec3().cwiseAbs() + Vec3::Constant(0.05);
    } else {
      const int count = shape == &input.a ? countA : countB;
      for (int i = 0; i < count; ++i) shape->points.push_back(reader.NextVec3());
    }
  }
  input.a.pose = ReadPose(reader);
  input.b.pose = ReadPose(reader);
  return input;
}

std::string CheckPairSat(const PairInput& input) {
  std::shared_ptr<const Hull> hulls[2];
  std::optional<Shape> shapes[2];
  const FuzzShape* parts[2] = {&input.a, &input.b};
  for (int i = 0; i < 2; ++i) {
    auto hull = parts[i]->box ? Hull::Box(parts[i]->halfExtents) : BuildHull(parts[i]->points);
    if (!hull) return {};  // a degenerate set; the hull_builder target checks refusals
    hulls[i] = std::make_shared<const Hull>(std::move(hull).Value());
    auto shape = Shape::CreateHull(hulls[i]);
    if (!shape) return "CreateHull refused a built hull: " + shape.GetError().message;
    shapes[i].emplace(std::move(shape).Value());
  }
  NarrowPhaseSettings settings;
  settings.satMode = input.satMode;
  auto answer = CollideShapes(*shapes[0], input.a.pose, *shapes[1], input.b.pose, settings);
  if (!answer) return "CollideShapes refused a valid pair: " + answer.GetError().message;
  const PairContact& contact = answer.Value();

  const WorldPolytope a = Place(*hulls[0], input.a.pose);
  const WorldPolytope b = Place(*hulls[1], input.b.pose);
  double reach = 0.0;
  for (const Vec3& va : a.vertices) {
    for (const Vec3& vb : b.vertices) reach = std::max(reach, (va - vb).norm());
  }
  const BruteForce brute = Sat(a, b, reach);
  const double roundOff = 64.0 * kEps * reach + a.tolerance + b.tolerance;
  if (brute.certainlySeparated && contact.touching) {
    return Describe("touching, but a brute-force axis separates the shapes by", brute.maxGap);
  }
  if (brute.certainlyOverlapping && !contact.touching) {
    return Describe("not touching, but every brute-force axis overlaps; largest gap", brute.maxGap);
  }
  if (!contact.normal.allFinite() || std::abs(contact.normal.norm() - 1.0) > 1e-9) return "normal not unit";
  if (!std::isfinite(contact.separation)) return "separation not finite";
  if (contact.touching) {
    // The least overlap over every axis is the exact minimum translation
    // distance; the SAT may prefer a face within its band.
    const double band = kPreferenceRelative * std::min(HalfDiagonal(*hulls[0]), HalfDiagonal(*hulls[1]));
    if (contact.separation > brute.maxGap + roundOff || contact.separation < brute.maxGap - band - roundOff) {
      return Describe("separation", contact.separation) +
             Describe(" against the brute force's", brute.maxGap) + Describe(" (band", band) + ")";
    }
    if (contact.pointCount < 1) return "touching without points";
  } else {
    // The reported normal, from B towards A, separates by the reported gap.
    const auto [lowA, highA] = Project(a.vertices, contact.normal);
    const auto [lowB, highB] = Project(b.vertices, contact.normal);
    const double gap = lowA - highB;
    if (std::abs(gap - contact.separation) > roundOff || contact.separation < -roundOff) {
      return Describe("not touching: reported gap", contact.separation) +
             Describe(", measured along its normal", gap);
    }
    if (contact.separation > brute.maxGap + roundOff) {
      return Describe("reported gap", contact.separation) +
             Describe(" above the brute force's best", brute.maxGap);
    }
  }
  return {};
}

}  // namespace talus::fuzz
