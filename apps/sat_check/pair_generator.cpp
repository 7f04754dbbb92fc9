// Pair generation (see the header). One std::mt19937_64 drives everything,
// drawn in a fixed order, so the pairs depend only on the seed.
#include "pair_generator.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <utility>

#include "talus/harness/support/random_draw.h"
#include "talus/hull_builder.h"

namespace talus::validation {
namespace {

using Draw = harness::RandomDraw;

// Half extents: the largest log-uniform in [lo, hi] m, the others that
// times an aspect ratio in [0.2, 1].
Vec3 Extents(Draw& draw, double lo, double hi) {
  const double size = lo * std::pow(hi / lo, draw.Uniform(0.0, 1.0));
  return Vec3(size, size * draw.Uniform(0.2, 1.0), size * draw.Uniform(0.2, 1.0));
}

Shape HullOnEllipsoid(Draw& draw, int count, const Vec3& extents) {
  for (;;) {
    std::vector<Vec3> points;
    for (int i = 0; i < count; ++i) points.push_back(draw.UnitVector().cwiseProduct(extents));
    Result<Hull> hull = BuildHull(points);
    if (hull) return Shape::CreateHull(std::make_shared<const Hull>(std::move(hull).Value())).Value();
  }
}

Shape MakeShape(Draw& draw, double lo, double hi) {
  const Vec3 extents = Extents(draw, lo, hi);
  if (draw.Integer(0, 1) == 0) return Shape::CreateBox(extents).Value();
  static constexpr int kCounts[] = {8, 16, 32, 64};
  return HullOnEllipsoid(draw, kCounts[draw.Integer(0, 3)], extents);
}

double LargestExtent(const Shape& shape) {
  const Aabb& box = shape.LocalAabb();
  return 0.5 * (box.max - box.min).maxCoeff();
}

// max over vertices of direction . (rotation * v), the support distance of
// the shape about its own origin.
double SupportDistance(const Shape& shape, const Quat& rotation, const Vec3& direction) {
  return direction.dot(rotation * shape.Support(rotation.conjugate() * direction));
}

}  // namespace

const char* ToString(Placement placement) {
  switch (placement) {
    case Placement::Separated:
      return "separated";
    case Placement::Touching:
      return "touching";
    case Placement::Shallow:
      return "shallow";
    case Placement::Deep:
      return "deep";
  }
  return "unknown";
}

const char* ToString(Alignment alignment) {
  switch (alignment) {
    case Alignment::Random:
      return "random";
    case Alignment::Face:
      return "face";
    case Alignment::Edge:
      return "edge";
  }
  return "unknown";
}

const char* ToString(Family family) {
  switch (family) {
    case Family::Standard:
      return "standard";
    case Family::Scaled:
      return "scaled";
    case Family::Far:
      return "far";
    case Family::Parallel:
      return "parallel";
    case Family::Identical:
      return "identical";
    case Family::Slab:
      return "slab";
    case Family::LargeParallel:
      return "largeParallel";
  }
  return "unknown";
}

namespace {

// The steps of one pair, each drawing from `draw` in the order the
// generator always has (the same seed gives the same pairs).

// The two shapes of a pair of `family`.
std::pair<Shape, Shape> DrawShapes(Draw& draw, Family family) {
  double lo = family == Family::Scaled ? 5e-4 : 0.1;  // half extents, metres
  double hi = family == Family::Scaled ? 5.0 : 2.0;
  if (family == Family::LargeParallel) {
    lo = 2.0;
    hi = 3.0;
  }
  Shape a = MakeShape(draw, lo, hi);
  Shape b = MakeShape(draw, lo, hi);
  if (family == Family::Identical) {
    b = a;
  } else if (family == Family::Slab) {
    const double scale = 0.25 * std::pow(8.0, draw.Uniform(0.0, 1.0));
    a = Shape::CreateBox(scale * Vec3(1.7, 0.002, 1.4)).Value();
    b = HullOnEllipsoid(draw, 36, Extents(draw, 0.1 * scale, 0.5 * scale));
  }
  return {std::move(a), std::move(b)};
}

// How the shapes are turned, and the direction n from B towards A along
// which the pair is placed.
struct Orientation {
  Quat rotationA;
  Quat rotationB;
  Vec3 n;
  double twist = 0.0;  // B's turn off A's face, rad (the parallel families)
};

// Face alignment: B against a face of A, turned like A (or, for the
// parallel families, nearly so).
void AlignFaces(Draw& draw, Family family, const Shape& a, const Shape& b, Orientation& o) {
  o.rotationB = o.rotationA;
  // A face normal of A (for a box one of its axes), reversed: B sits
  // against that face.
  const auto faces = a.GetHull().Faces();
  const Vec3 localNormal =
      faces[static_cast<std::size_t>(draw.Integer(0, static_cast<int>(faces.size()) - 1))].plane.normal;
  o.n = -(o.rotationA * localNormal);
  // Nearly parallel faces: B turned by 1e-6 rad.
  if (family == Family::Parallel) {
    o.twist = 1e-6;
    o.rotationB = Quat(Eigen::AngleAxisd(o.twist, draw.UnitVector())) * o.rotationA;
  }
  // Large shapes: a face of B turned to point along n (towards A.s
  // face), spun about n, then twisted 1e-8 to 1e-6 rad.
  if (family == Family::LargeParallel) {
    const auto facesB = b.GetHull().Faces();
    const Vec3 normalB =
        facesB[static_cast<std::size_t>(draw.Integer(0, static_cast<int>(facesB.size()) - 1))].plane.normal;
    const Quat spin(Eigen::AngleAxisd(draw.Uniform(0.0, 2.0 * std::numbers::pi), o.n));
    o.twist = kLargeParallelTwistMin *
              std::pow(kLargeParallelTwistMax / kLargeParallelTwistMin, draw.Uniform(0.0, 1.0));
    o.rotationB =
        (Quat(Eigen::AngleAxisd(o.twist, draw.UnitVector())) * spin * Quat::FromTwoVectors(normalB, o.n))
            .normalized();
  }
}

Orientation DrawOrientation(Draw& draw, Family family, Alignment alignment, const Shape& a, const Shape& b) {
  Orientation o;
  o.rotationA = draw.Rotation();
  o.rotationB = draw.Rotation();
  o.n = draw.UnitVector();
  if (alignment == Alignment::Face) {
    AlignFaces(draw, family, a, b, o);
  } else if (alignment == Alignment::Edge) {
    const int first = draw.Integer(0, 2);
    const int second = (first + 1 + draw.Integer(0, 1)) % 3;
    o.rotationB = o.rotationA * Quat(Eigen::AngleAxisd(0.25 * std::numbers::pi, Vec3::Unit(first))) *
                  Quat(Eigen::AngleAxisd(0.25 * std::numbers::pi, Vec3::Unit(second)));
  }
  return o;
}

// The gap the placement asks for (m; negative: overlap), scaled by `size`.
double DrawGap(Draw& draw, Placement placement, Family family, double size) {
  double gap = 0.0;
  switch (placement) {
    case Placement::Separated:
      gap = size * draw.Uniform(0.01, 0.5);
      break;
    case Placement::Touching:
      gap = size * draw.Uniform(-1e-9, 1e-9);
      break;
    case Placement::Shallow:
      gap = family == Family::Identical ? -size * std::pow(10.0, draw.Uniform(-5.0, -2.0))
                                        : -size * draw.Uniform(1e-3, 0.05);
      break;
    case Placement::Deep:
      gap = -size * draw.Uniform(0.1, 0.8);
      break;
  }
  return gap;
}

// A's position, and B's: `gap` apart along n, with a small offset across it.
std::pair<Vec3, Vec3> DrawPositions(Draw& draw, Family family, const Shape& a, const Shape& b,
                                    const Orientation& o, double size, double gap) {
  const Vec3& n = o.n;
  Vec3 positionA(draw.Uniform(-1.0, 1.0), draw.Uniform(-1.0, 1.0), draw.Uniform(-1.0, 1.0));
  if (family == Family::Far) positionA = draw.UnitVector() * std::pow(10.0, draw.Uniform(4.0, 5.0));
  if (family == Family::Scaled) positionA *= size;  // near the origin at the shapes' own scale
  // A small offset across n, so face-aligned pairs are not centred.
  Vec3 lateral = draw.UnitVector();
  lateral -= n * n.dot(lateral);
  lateral *= draw.Uniform(0.0, 0.3) * size;
  // Identical shapes go straight along the face normal: a copy moved
  // sideways off a curved face need not touch at all.
  if (family == Family::Identical) lateral = Vec3::Zero();
  // Along n, B's extent (towards A) and A's (towards B) meet at gap 0.
  const double reach = SupportDistance(b, o.rotationB, n) + SupportDistance(a, o.rotationA, -n);
  const double along = reach + gap;
  return {positionA, positionA - n * along + lateral};
}

ShapePair DrawPair(Draw& draw, int index) {
  const auto family = static_cast<Family>(index % kFamilyCount);
  auto [a, b] = DrawShapes(draw, family);
  auto placement = static_cast<Placement>(draw.Integer(0, 3));
  auto alignment = static_cast<Alignment>(draw.Integer(0, 2));
  if (family == Family::Parallel || family == Family::LargeParallel) alignment = Alignment::Face;
  if (family == Family::Identical) {
    alignment = Alignment::Face;
    placement = Placement::Shallow;
  }
  const double size = std::min(LargestExtent(a), LargestExtent(b));
  const Orientation o = DrawOrientation(draw, family, alignment, a, b);
  const double gap = DrawGap(draw, placement, family, size);
  const auto [positionA, positionB] = DrawPositions(draw, family, a, b, o, size, gap);
  return {.index = index,
          .a = std::move(a),
          .b = std::move(b),
          .xfA = {.position = positionA, .rotation = o.rotationA},
          .xfB = {.position = positionB, .rotation = o.rotationB},
          .placement = placement,
          .alignment = alignment,
          .family = family,
          .targetGap = gap,
          .size = size,
          .twist = o.twist};
}

}  // namespace

std::vector<ShapePair> GeneratePairs(int count, std::uint64_t seed) {
  Draw draw{std::mt19937_64(seed)};
  std::vector<ShapePair> pairs;
  pairs.reserve(static_cast<std::size_t>(std::max(count, 0)));
  for (int i = 0; i < count; ++i) pairs.push_back(DrawPair(draw, i));
  return pairs;
}

std::string Describe(const ShapePair& pair) {
  std::ostringstream out;
  out.precision(3);
  const auto shape = [&out](const Shape& s) {
    if (s.Type() == ShapeType::Box) {
      const Vec3& h = s.HalfExtents();
      out << "box " << h.x() << "x" << h.y() << "x" << h.z();
    } else {
      out << "hull " << s.GetHull().VertexCount() << "v";
    }
  };
  shape(pair.a);
  out << " vs ";
  shape(pair.b);
  out << ", " << ToString(pair.family) << ", " << ToString(pair.alignment) << ", "
      << ToString(pair.placement);
  return out.str();
}

}  // namespace talus::validation
