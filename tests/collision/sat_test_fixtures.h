// Shared fixtures for the narrow-phase tests: shapes built by Quickhull
// from point sets (boxes, tetrahedra, octahedra, prisms, random clouds),
// random rigid transforms, and brute-force oracles that measure an axis by
// projecting every vertex. Randomness comes from caller-owned generators
// with fixed seeds, so every run sees the same cases.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include "collision/posed_hull.h"
#include "talus/hull_builder.h"
#include "talus/shape.h"
#include "talus/transform.h"

namespace talus::test {

inline Shape HullShape(const std::vector<Vec3>& points) {
  auto hull = BuildHull(points);
  EXPECT_TRUE(hull) << hull.GetError().message;
  return Shape::CreateHull(std::make_shared<const Hull>(std::move(hull).Value())).Value();
}

inline Shape BoxShape(const Vec3& halfExtents) { return Shape::CreateBox(halfExtents).Value(); }

inline std::vector<Vec3> BoxPoints(const Vec3& e) {
  std::vector<Vec3> points;
  for (int i = 0; i < 8; ++i)
    points.emplace_back(i & 1 ? e.x() : -e.x(), i & 2 ? e.y() : -e.y(), i & 4 ? e.z() : -e.z());
  return points;
}

/// A regular-ish tetrahedron, an octahedron and a hexagonal prism of unit size.
inline std::vector<Vec3> TetrahedronPoints() { return {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}}; }
inline std::vector<Vec3> OctahedronPoints() {
  return {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
}
inline std::vector<Vec3> PrismPoints(int sides) {
  std::vector<Vec3> points;
  for (int i = 0; i < sides; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / sides;
    points.emplace_back(std::cos(angle), -0.5, std::sin(angle));
    points.emplace_back(std::cos(angle), 0.5, std::sin(angle));
  }
  return points;
}

/// `count` random points in a unit ball's shell (0.5..1), hull about the origin.
inline std::vector<Vec3> CloudPoints(std::mt19937_64& rng, int count) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> radius(0.5, 1.0);
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) {
    Vec3 d(normal(rng), normal(rng), normal(rng));
    points.push_back(d.normalized() * radius(rng));
  }
  return points;
}

inline Quat RandomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Quat q(normal(rng), normal(rng), normal(rng), normal(rng));
  q.normalize();
  return q;
}

inline Vec3 RandomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  return Vec3(normal(rng), normal(rng), normal(rng)).normalized();
}

/// Two shapes and their poses, as a pair query takes them.
struct PosedShapes {
  Shape a;
  Shape b;
  Transform xfA;
  Transform xfB;
};

/// How far world point `x` lies outside the posed shape (metres, <= 0
/// inside): the largest signed distance to its own face planes.
inline double OutsideShape(const Shape& shape, const Transform& xf, const Vec3& x) {
  const Vec3 local = xf.ApplyInverse(x);
  double worst = -std::numeric_limits<double>::infinity();
  for (const HullFace& face : shape.GetHull().Faces())
    worst = std::max(worst, face.plane.SignedDistance(local));
  return worst;
}

/// Round-off of one pair query (metres): a depth or a point's plane
/// distance is a difference of dot products of world coordinates as large
/// as the positions plus the shapes' extents, and each rounds a few ulps of
/// those; 64 ulps of their sum covers them with margin (the SAT check's
/// figure).
inline double PairRoundOff(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB) {
  const double coordinates =
      std::max(xfA.position.cwiseAbs().maxCoeff(), xfB.position.cwiseAbs().maxCoeff()) +
      2.0 * std::max(a.LocalAabb().max.cwiseAbs().maxCoeff(), b.LocalAabb().max.cwiseAbs().maxCoeff());
  return 64.0 * std::numeric_limits<double>::epsilon() * coordinates;
}

/// A random shape of the kinds above, scaled non-uniformly (0.3..1.5 per axis).
inline Shape RandomPolyhedron(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 5);
  std::uniform_real_distribution<double> scale(0.3, 1.5);
  const Vec3 s(scale(rng), scale(rng), scale(rng));
  std::vector<Vec3> points;
  switch (kind(rng)) {
    case 0:
      return BoxShape(s);
    case 1:
      points = TetrahedronPoints();
      break;
    case 2:
      points = OctahedronPoints();
      break;
    case 3:
      points = PrismPoints(3 + static_cast<int>(rng() % 5));
      break;
    case 4:
      points = BoxPoints(Vec3::Ones());
      break;
    default:
      points = CloudPoints(rng, 8 + static_cast<int>(rng() % 24));
      break;
  }
  for (Vec3& p : points) p = p.cwiseProduct(s);
  return HullShape(points);
}

/// Brute-force support distance of a posed hull along `d`.
inline double BruteSupport(const PosedHull& p, const Vec3& d) {
  double best = -std::numeric_limits<double>::infinity();
  for (int v = 0; v < p.hull->VertexCount(); ++v) best = std::max(best, d.dot(p.Vertex(v)));
  return best;
}

/// Overlap of the two projections on unit axis n (negative: a gap).
inline double BruteOverlap(const PosedHull& a, const PosedHull& b, const Vec3& n) {
  const double alongPlus = BruteSupport(a, n) + BruteSupport(b, -n);
  const double alongMinus = BruteSupport(a, -n) + BruteSupport(b, n);
  return std::min(alongPlus, alongMinus);
}

/// The write-up's SAT done naively: least overlap over every face normal
/// and every edge cross product, each measured by projecting all vertices.
inline double BruteMinimumOverlap(const PosedHull& a, const PosedHull& b) {
  double best = std::numeric_limits<double>::infinity();
  for (const PosedHull* p : {&a, &b}) {
    for (int f = 0; f < p->hull->FaceCount(); ++f)
      best = std::min(best, BruteOverlap(a, b, p->FaceNormal(f)));
  }
  for (int ea = 0; ea < a.hull->EdgeCount(); ++ea) {
    for (int eb = 0; eb < b.hull->EdgeCount(); ++eb) {
      const Vec3 da = a.EdgeDirection(ea);
      const Vec3 db = b.EdgeDirection(eb);
      const Vec3 c = da.cross(db);
      if (c.norm() <= 1e-6 * da.norm() * db.norm()) continue;
      best = std::min(best, BruteOverlap(a, b, c.normalized()));
    }
  }
  return best;
}

}  // namespace talus::test
