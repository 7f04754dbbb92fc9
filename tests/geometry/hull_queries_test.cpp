// Hull queries against brute-force oracles and analytic answers on boxes,
// regular solids and random affine images of them.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "geometry/polyhedra.h"
#include "talus/hull_builder.h"
#include "talus/hull_queries.h"
#include "talus/mass_properties.h"

namespace talus {
namespace hull_queries_test {

using test::MakeHull;

// Number of random hulls per property: enough to hit every base shape many
// times, small enough for the sanitizer build.
constexpr int kTrials = 300;

double Extent(const Hull& hull) {
  double extent = 0.0;
  for (const Vec3& v : hull.Vertices()) extent = std::max(extent, v.norm());
  return extent;
}

TEST(SupportVertex, MatchesBruteForceFromEveryStartOnRandomHulls) {
  std::mt19937_64 rng(1);
  for (int trial = 0; trial < kTrials; ++trial) {
    const Hull hull = MakeHull(test::RandomConvexPolygons(rng));
    for (int k = 0; k < 10; ++k) {
      const Vec3 d = test::RandomDirection(rng) * std::exp(static_cast<double>(k) - 5.0);
      const double best = d.dot(hull.Vertices()[static_cast<std::size_t>(SupportVertexBruteForce(hull, d))]);
      for (int start = 0; start < hull.VertexCount(); ++start) {
        const int v = SupportVertex(hull, d, start);
        // Ties may pick another vertex, so compare support values; both
        // are the same dot products, equal up to the rounding of one.
        EXPECT_NEAR(d.dot(hull.Vertices()[static_cast<std::size_t>(v)]), best,
                    1e-12 * d.norm() * Extent(hull))
            << "trial " << trial << " start " << start;
      }
    }
  }
}

TEST(SupportVertex, TerminatesOnPlateausOfTiedVertices) {
  const Hull box = Hull::Box({1, 2, 3}).Value();
  // Axis directions tie a whole face (4 vertices); zero ties all 8.
  for (const Vec3& d : {Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(1, 1, 0), Vec3::Zero().eval()}) {
    for (int start = 0; start < box.VertexCount(); ++start) {
      const int v = SupportVertex(box, d, start);
      EXPECT_EQ(d.dot(box.Vertices()[static_cast<std::size_t>(v)]),
                d.dot(box.Vertices()[static_cast<std::size_t>(SupportVertexBruteForce(box, d))]));
    }
  }
}

TEST(SupportVertex, FindsThePoleOfAFineUvSphereFromTheOtherPole) {
  const Hull sphere = MakeHull(test::UvSpherePolygons(1.0, 32, 64), 1e-12);
  const int north = SupportVertex(sphere, Vec3(0, 0, 1), sphere.VertexCount() - 1);
  EXPECT_EQ(sphere.Vertices()[static_cast<std::size_t>(north)], Vec3(0, 0, 1));
}

TEST(ContainsPoint, BoxContainsExactlyItsClosedRegion) {
  const Hull box = Hull::Box({1, 2, 3}).Value();
  EXPECT_TRUE(ContainsPoint(box, Vec3(0.9, -1.9, 2.9)));
  EXPECT_TRUE(ContainsPoint(box, Vec3(1, 2, 3)));  // a corner is on the surface
  EXPECT_FALSE(ContainsPoint(box, Vec3(1.001, 0, 0)));
  EXPECT_TRUE(ContainsPoint(box, Vec3(1.001, 0, 0), 0.002));
  EXPECT_FALSE(ContainsPoint(box, Vec3(0, 0, -3.1), 0.05));
  EXPECT_FALSE(ContainsPoint(box, Vec3(0, std::numeric_limits<double>::quiet_NaN(), 0)));
}

// Convex combinations of vertices are inside; a point pushed off a face by
// delta along its normal is outside, and inside again with tolerance delta.
TEST(ContainsPoint, AgreesWithConvexCombinationsAndOffsetFacePoints) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < kTrials; ++trial) {
    const Hull hull = MakeHull(test::RandomConvexPolygons(rng));
    std::vector<double> weights;
    double sum = 0.0;
    for (int v = 0; v < hull.VertexCount(); ++v) sum += weights.emplace_back(unit(rng));
    Vec3 inside = Vec3::Zero();
    for (int v = 0; v < hull.VertexCount(); ++v) {
      inside += weights[static_cast<std::size_t>(v)] / sum * hull.Vertices()[static_cast<std::size_t>(v)];
    }
    EXPECT_TRUE(ContainsPoint(hull, inside, 1e-12 * Extent(hull))) << "trial " << trial;
    for (int f = 0; f < hull.FaceCount(); ++f) {
      const std::vector<int> loop = hull.FaceVertices(f);
      Vec3 center = Vec3::Zero();
      for (int v : loop) center += hull.Vertices()[static_cast<std::size_t>(v)];
      center /= static_cast<double>(loop.size());
      const double delta = 1e-3;
      const Vec3 outside = center + delta * hull.Faces()[static_cast<std::size_t>(f)].plane.normal;
      EXPECT_FALSE(ContainsPoint(hull, outside)) << "trial " << trial << " face " << f;
      EXPECT_TRUE(ContainsPoint(hull, outside, 1.001 * delta)) << "trial " << trial << " face " << f;
    }
  }
}

TEST(RayCast, HitsBoxFaceAtAnalyticDistanceWithItsNormal) {
  const Hull box = Hull::Box({1, 2, 3}).Value();
  const auto hit = RayCast(box, Vec3(-5, 0.5, 0.5), Vec3(2, 0, 0), 100.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_DOUBLE_EQ(hit->distance, 4.0);
  EXPECT_EQ(hit->normal, Vec3(-1, 0, 0));
  EXPECT_EQ(box.Faces()[static_cast<std::size_t>(hit->face)].plane.normal, Vec3(-1, 0, 0));

  const Vec3 diagonal = Vec3(1, 1, 1).normalized();
  const auto corner = RayCast(box, Vec3(-4, -4, -4), diagonal, 100.0);
  ASSERT_TRUE(corner.has_value());
  // Enters through the -x face at x = -1: three units along x.
  EXPECT_NEAR(corner->distance, 3.0 * std::sqrt(3.0), 1e-14);
}

TEST(RayCast, MissesWhenStartingInsidePointingAwayOrTooShort) {
  const Hull box = Hull::Box({1, 1, 1}).Value();
  EXPECT_FALSE(RayCast(box, Vec3(0, 0, 0), Vec3(1, 0, 0), 10.0).has_value()) << "starts inside";
  EXPECT_FALSE(RayCast(box, Vec3(3, 0, 0), Vec3(1, 0, 0), 10.0).has_value()) << "points away";
  EXPECT_FALSE(RayCast(box, Vec3(3, 0, 0), Vec3(-1, 0, 0), 1.5).has_value()) << "stops short";
  EXPECT_TRUE(RayCast(box, Vec3(3, 0, 0), Vec3(-1, 0, 0), 2.0).has_value()) << "reaches exactly";
  EXPECT_FALSE(RayCast(box, Vec3(3, 1.5, 0), Vec3(-1, 0, 0), 10.0).has_value()) << "passes beside";
  EXPECT_FALSE(RayCast(box, Vec3(-3, 2, 0), Vec3(1, 0, 0), 10.0).has_value()) << "parallel, outside";
}

// Oracle: bisection on ContainsPoint between an outside origin and an
// interior target finds the entry distance to ~1e-13 m, independently of
// the face-plane clipping.
TEST(RayCast, EntryDistanceMatchesBisectionOnRandomHulls) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < kTrials; ++trial) {
    const Hull hull = MakeHull(test::RandomConvexPolygons(rng));
    const Vec3 target = ComputeMassProperties(hull, 1.0).Value().centerOfMass;
    const Vec3 origin = target + 3.0 * Extent(hull) * test::RandomDirection(rng);
    const Vec3 direction = target - origin;
    const double length = direction.norm();
    const auto hit = RayCast(hull, origin, direction, 2.0 * length);
    ASSERT_TRUE(hit.has_value()) << "trial " << trial;
    double outside = 0.0;
    double inside = length;
    for (int i = 0; i < 200 && inside - outside > 1e-14 * length; ++i) {
      const double mid = 0.5 * (outside + inside);
      (ContainsPoint(hull, origin + mid * direction / length) ? inside : outside) = mid;
    }
    EXPECT_NEAR(hit->distance, inside, 1e-11 * length) << "trial " << trial;
    const Plane& plane = hull.Faces()[static_cast<std::size_t>(hit->face)].plane;
    EXPECT_EQ(hit->normal, plane.normal);
    EXPECT_NEAR(plane.SignedDistance(origin + hit->distance * direction / length), 0.0, 1e-11 * length)
        << "the hit point lies on the reported face's plane";
    EXPECT_FALSE(RayCast(hull, target, direction, 2.0 * length).has_value()) << "from inside";
    EXPECT_FALSE(RayCast(hull, origin, -direction, 2.0 * length).has_value()) << "away";
  }
}

PlaneSide BruteForceSide(const Hull& hull, const Plane& plane, double tolerance) {
  double lowest = std::numeric_limits<double>::infinity();
  double highest = -lowest;
  for (const Vec3& v : hull.Vertices()) {
    lowest = std::min(lowest, plane.SignedDistance(v));
    highest = std::max(highest, plane.SignedDistance(v));
  }
  if (lowest > tolerance) return PlaneSide::Front;
  if (highest < -tolerance) return PlaneSide::Back;
  return PlaneSide::Crossing;
}

TEST(ClassifyPlane, MatchesBruteForceOnRandomHullsAndPlanes) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> offset(-20.0, 20.0);
  for (int trial = 0; trial < kTrials; ++trial) {
    const Hull hull = MakeHull(test::RandomConvexPolygons(rng));
    for (int k = 0; k < 20; ++k) {
      const Plane plane{.normal = test::RandomDirection(rng), .offset = offset(rng)};
      EXPECT_EQ(ClassifyPlane(hull, plane, 0.01), BruteForceSide(hull, plane, 0.01)) << "trial " << trial;
    }
  }
}

TEST(ClassifyPlane, TouchingWithinToleranceCountsAsCrossing) {
  const Hull box = Hull::Box({1, 1, 1}).Value();
  EXPECT_EQ(ClassifyPlane(box, {.normal = Vec3::UnitX(), .offset = 1.5}), PlaneSide::Back);
  EXPECT_EQ(ClassifyPlane(box, {.normal = Vec3::UnitX(), .offset = -1.5}), PlaneSide::Front);
  EXPECT_EQ(ClassifyPlane(box, {.normal = Vec3::UnitX(), .offset = 0.0}), PlaneSide::Crossing);
  EXPECT_EQ(ClassifyPlane(box, {.normal = Vec3::UnitX(), .offset = 1.05}, 0.1), PlaneSide::Crossing);
  EXPECT_EQ(ClassifyPlane(box, {.normal = Vec3::UnitX(), .offset = 1.05}, 0.01), PlaneSide::Back);
}

TEST(BoundingSpheres, BoxSpheresAreCentredWithHalfDiagonalRadius) {
  const Vec3 e(1, 2, 3);
  const Vec3 offset(5, -7, 9);
  const Hull box = MakeHull(test::BoxPolygons(e, offset));
  for (const Sphere& s : {CentroidBoundingSphere(box), TightBoundingSphere(box)}) {
    EXPECT_LE((s.center - offset).norm(), 1e-13);
    EXPECT_NEAR(s.radius, e.norm(), 1e-13);
  }
}

// The minimum enclosing ball of a point set has 2 to 4 of the points on its
// boundary, so the smallest ball through some 2, 3 or 4 vertices that holds
// every vertex is the answer. Centres here come from Eigen's LU solves, not
// from the closed forms in the engine.
Sphere BruteForceMinimumSphere(const Hull& hull) {
  const auto p = hull.Vertices();
  const std::size_t n = p.size();
  Sphere best{.center = Vec3::Zero(), .radius = std::numeric_limits<double>::infinity()};
  const auto consider = [&](const Vec3& center) {
    double radius = 0.0;
    for (const Vec3& v : p) radius = std::max(radius, (v - center).norm());
    if (radius < best.radius) best = {.center = center, .radius = radius};
  };
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      consider(0.5 * (p[i] + p[j]));
      for (std::size_t k = j + 1; k < n; ++k) {
        // Circumcentre of a triangle: equidistant from the three, in their plane.
        Mat3 a;
        a.row(0) = p[j] - p[i];
        a.row(1) = p[k] - p[i];
        a.row(2) = (p[j] - p[i]).cross(p[k] - p[i]);
        const Vec3 rhs(0.5 * a.row(0).squaredNorm(), 0.5 * a.row(1).squaredNorm(), 0.0);
        if (std::abs(a.determinant()) > 1e-12) consider(p[i] + a.partialPivLu().solve(rhs));
        for (std::size_t l = k + 1; l < n; ++l) {
          Mat3 b;
          b.row(0) = p[j] - p[i];
          b.row(1) = p[k] - p[i];
          b.row(2) = p[l] - p[i];
          const Vec3 rhs4(0.5 * b.row(0).squaredNorm(), 0.5 * b.row(1).squaredNorm(),
                          0.5 * b.row(2).squaredNorm());
          if (std::abs(b.determinant()) > 1e-12) consider(p[i] + b.partialPivLu().solve(rhs4));
        }
      }
    }
  }
  return best;
}

TEST(BoundingSpheres, TightSphereIsTheMinimumEnclosingSphereOnRandomHulls) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < kTrials / 3; ++trial) {
    const Hull hull = MakeHull(test::RandomConvexPolygons(rng));
    const Sphere tight = TightBoundingSphere(hull);
    const Sphere oracle = BruteForceMinimumSphere(hull);
    EXPECT_NEAR(tight.radius, oracle.radius, 1e-9 * oracle.radius) << "trial " << trial;
  }
}

TEST(BoundingSpheres, BothSpheresHoldEveryVertexAndTightIsNeverLarger) {
  std::mt19937_64 rng(6);
  for (int trial = 0; trial < kTrials; ++trial) {
    const Hull hull = MakeHull(test::RandomConvexPolygons(rng));
    const Sphere centroid = CentroidBoundingSphere(hull);
    const Sphere tight = TightBoundingSphere(hull);
    EXPECT_LE(tight.radius, centroid.radius) << "trial " << trial;
    EXPECT_LE((centroid.center - ComputeMassProperties(hull, 1.0).Value().centerOfMass).norm(), 0.0);
    for (const Vec3& v : hull.Vertices()) {
      EXPECT_LE((v - centroid.center).norm(), centroid.radius * (1.0 + 1e-12)) << "trial " << trial;
      EXPECT_LE((v - tight.center).norm(), tight.radius * (1.0 + 1e-12)) << "trial " << trial;
    }
    const Sphere again = TightBoundingSphere(hull);
    EXPECT_EQ(again.center, tight.center) << "deterministic";
    EXPECT_EQ(again.radius, tight.radius) << "deterministic";
  }
}

// A square pyramid with a tall apex: its volume centroid sits low (a
// quarter of the height), so the centroid sphere is far looser than the
// minimum sphere, whose centre is found analytically from |c - apex| =
// |c - base corner| on the axis.
TEST(BoundingSpheres, TightSphereOfTallPyramidIsTheAnalyticMinimum) {
  const double h = 4.0;
  test::Polygons pyramid{.vertices = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 0, h}},
                         .faces = {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}}};
  const Hull hull = MakeHull(pyramid);
  const double z = (h * h - 2.0) / (2.0 * h);  // equidistant from apex and base corners
  const Sphere tight = TightBoundingSphere(hull);
  EXPECT_LE((tight.center - Vec3(0, 0, z)).norm(), 1e-13);
  EXPECT_NEAR(tight.radius, h - z, 1e-13);
  const Sphere centroid = CentroidBoundingSphere(hull);
  EXPECT_NEAR(centroid.center.z(), h / 4.0, 1e-13);
  EXPECT_NEAR(centroid.radius, 0.75 * h, 1e-13);
  EXPECT_LT(tight.radius, 0.85 * centroid.radius);
}

TEST(ComputeAabb, MatchesBoxAndBruteForceOnRandomHulls) {
  const Aabb box = ComputeAabb(MakeHull(test::BoxPolygons(Vec3(1, 2, 3), Vec3(10, 0, -1))));
  EXPECT_EQ(box.min, Vec3(9, -2, -4));
  EXPECT_EQ(box.max, Vec3(11, 2, 2));
  std::mt19937_64 rng(8);
  for (int trial = 0; trial < kTrials; ++trial) {
    const Hull hull = MakeHull(test::RandomConvexPolygons(rng));
    const Aabb aabb = ComputeAabb(hull);
    for (int axis = 0; axis < 3; ++axis) {
      const Vec3 d = Vec3::Unit(axis);
      EXPECT_EQ(aabb.max(axis),
                hull.Vertices()[static_cast<std::size_t>(SupportVertexBruteForce(hull, d))](axis));
      EXPECT_EQ(aabb.min(axis),
                hull.Vertices()[static_cast<std::size_t>(SupportVertexBruteForce(hull, -d))](axis));
    }
  }
}

// Quickhull of random clouds gives hulls with many vertices and
// irregular, mostly triangular faces: a harder walk for hill climbing and
// more candidates for Welzl's loops than the closed-form shapes above.
TEST(HullQueries, SupportAndSpheresHoldOnQuickhullsOfRandomClouds) {
  std::mt19937_64 rng(9);
  std::normal_distribution<double> gauss;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Vec3> points;
    for (int i = 0; i < 300; ++i) points.emplace_back(gauss(rng), 2.0 * gauss(rng), 0.5 * gauss(rng));
    auto built = BuildHull(points);
    ASSERT_TRUE(built) << built.GetError().message;
    const Hull& hull = built.Value();
    for (int k = 0; k < 50; ++k) {
      const Vec3 d = test::RandomDirection(rng);
      const int start = static_cast<int>(rng() % static_cast<std::uint64_t>(hull.VertexCount()));
      const Vec3& found = hull.Vertices()[static_cast<std::size_t>(SupportVertex(hull, d, start))];
      const Vec3& best = hull.Vertices()[static_cast<std::size_t>(SupportVertexBruteForce(hull, d))];
      EXPECT_NEAR(d.dot(found), d.dot(best), 1e-12 * Extent(hull)) << "trial " << trial;
    }
    const Sphere tight = TightBoundingSphere(hull);
    EXPECT_LE(tight.radius, CentroidBoundingSphere(hull).radius);
    for (const Vec3& p : points) {
      EXPECT_LE((p - tight.center).norm(), tight.radius * (1.0 + 1e-12))
          << "every input point, not only vertices";
      EXPECT_TRUE(ContainsPoint(hull, p, 1e-9)) << "trial " << trial;
    }
  }
}

}  // namespace hull_queries_test
}  // namespace talus
