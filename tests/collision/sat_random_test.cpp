// SAT properties over thousands of random polyhedron pairs (fixed seeds):
// against a brute-force oracle that projects every vertex on every
// candidate axis, between modes (full, pruned, cached), under a rigid
// motion of both shapes, and under swapping A and B.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "collision/collide.h"
#include "collision/sat.h"
#include "collision/sat_test_fixtures.h"
#include "talus/hull_queries.h"

namespace talus {
namespace sat_random_test {

// Round-off bound for comparing one axis measured two ways on shapes of
// size ~1 m at distances ~1 m: a few hundred ulps.
constexpr double kRoundOff = 1e-12;

struct Pair {
  Shape a;
  Shape b;
  Transform xfA;
  Transform xfB;
};

// B placed at a random distance up to 1.4 x the sum of bounding radii, so
// about half the pairs overlap.
std::vector<Pair> RandomPairs(std::uint64_t seed, int count) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Pair> pairs;
  for (int i = 0; i < count; ++i) {
    Shape a = test::RandomPolyhedron(rng);
    Shape b = test::RandomPolyhedron(rng);
    const double reach = a.LocalBoundingSphere().radius + b.LocalBoundingSphere().radius;
    const Transform xfA{.position = Vec3(unit(rng), unit(rng), unit(rng)),
                        .rotation = test::RandomRotation(rng)};
    const Transform xfB{.position = xfA.position + test::RandomUnit(rng) * (0.9 * reach * unit(rng)),
                        .rotation = test::RandomRotation(rng)};
    pairs.push_back({std::move(a), std::move(b), xfA, xfB});
  }
  return pairs;
}

SatResult Sat(const Pair& p, SatMode mode, SatCache* cache = nullptr, NarrowPhaseStats* stats = nullptr) {
  return RunSat(PosedHull::Make(p.a.GetHull(), p.xfA), PosedHull::Make(p.b.GetHull(), p.xfB), mode, 0.0,
                cache, stats);
}

TEST(SatRandom, VerdictDepthAndNormalMatchBruteForceOverAllAxes) {
  int overlapping = 0;
  for (const Pair& p : RandomPairs(1, 1500)) {
    const PosedHull a = PosedHull::Make(p.a.GetHull(), p.xfA);
    const PosedHull b = PosedHull::Make(p.b.GetHull(), p.xfB);
    const double oracle = test::BruteMinimumOverlap(a, b);
    const SatResult sat = Sat(p, SatMode::GaussMapPruned);
    if (std::abs(oracle) < 1e-9) continue;  // touching: either verdict is right
    ASSERT_EQ(sat.separated, oracle < 0.0) << "oracle overlap " << oracle;
    // The reported normal really is measured as reported (B towards A).
    EXPECT_NEAR(test::BruteOverlap(a, b, sat.normal), -sat.separation, kRoundOff);
    if (sat.separated) continue;
    ++overlapping;
    // Depth is the least overlap, up to the face preference bias.
    EXPECT_GE(sat.separation, -oracle - kRoundOff);
    EXPECT_LE(-sat.separation, oracle + AxisPreferenceBand(p.a.GetHull(), p.b.GetHull()) + kRoundOff);
    // A along +normal and B along -normal: B's support along the normal
    // minus A's support against it is the depth.
    EXPECT_NEAR(test::BruteSupport(b, sat.normal) + test::BruteSupport(a, -sat.normal), -sat.separation,
                kRoundOff);
  }
  EXPECT_GT(overlapping, 300);
}

TEST(SatRandom, DepthIsNoMoreThanTheOverlapAlongAnyDirection) {
  std::mt19937_64 rng(2);
  for (const Pair& p : RandomPairs(3, 300)) {
    const SatResult sat = Sat(p, SatMode::GaussMapPruned);
    if (sat.separated) continue;
    const PosedHull a = PosedHull::Make(p.a.GetHull(), p.xfA);
    const PosedHull b = PosedHull::Make(p.b.GetHull(), p.xfB);
    for (int i = 0; i < 200; ++i) {
      EXPECT_GE(test::BruteOverlap(a, b, test::RandomUnit(rng)),
                -sat.separation - AxisPreferenceBand(p.a.GetHull(), p.b.GetHull()));
    }
  }
}

TEST(SatRandom, KnownSeparatedPairsReportNoContactAndSharedPointsDo) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> gap(1e-6, 0.5);
  for (int i = 0; i < 1000; ++i) {
    const Shape a = test::RandomPolyhedron(rng);
    const Shape b = test::RandomPolyhedron(rng);
    const Transform xfA{.position = Vec3::Zero(), .rotation = test::RandomRotation(rng)};
    Transform xfB{.position = Vec3::Zero(), .rotation = test::RandomRotation(rng)};
    // Both contain the origin (every fixture is built around it): overlap.
    ASSERT_FALSE(Sat({a, b, xfA, xfB}, SatMode::GaussMapPruned).separated);
    ASSERT_FALSE(Sat({a, b, xfA, xfB}, SatMode::Full).separated);
    // Slide B along u until a plane normal to u separates them by `gap`.
    const Vec3 u = test::RandomUnit(rng);
    const PosedHull pa = PosedHull::Make(a.GetHull(), xfA);
    const PosedHull pb = PosedHull::Make(b.GetHull(), xfB);
    xfB.position = u * (test::BruteSupport(pa, u) + test::BruteSupport(pb, -u) + gap(rng));
    ASSERT_TRUE(Sat({a, b, xfA, xfB}, SatMode::GaussMapPruned).separated);
    ASSERT_TRUE(Sat({a, b, xfA, xfB}, SatMode::Full).separated);
  }
}

TEST(SatRandom, PrunedAndFullAgreeOnVerdictDepthAndAxis) {
  NarrowPhaseStats full;
  NarrowPhaseStats pruned;
  int sameAxis = 0;
  int overlapping = 0;
  for (const Pair& p : RandomPairs(5, 1500)) {
    const SatResult f = Sat(p, SatMode::Full, nullptr, &full);
    const SatResult g = Sat(p, SatMode::GaussMapPruned, nullptr, &pruned);
    ASSERT_EQ(f.separated, g.separated);
    if (f.separated) continue;
    ++overlapping;
    EXPECT_EQ(f.separation, g.separation);
    EXPECT_NEAR((f.normal - g.normal).norm(), 0.0, kRoundOff);
    if (f.axis == g.axis) ++sameAxis;
  }
  // Ties (parallel edges giving one axis) are the only excuse for a
  // different axis; canonical supporting edges make even those rare.
  EXPECT_GE(sameAxis, overlapping - overlapping / 100);
  EXPECT_GT(pruned.edgePairsPruned, 0u);
  EXPECT_LT(pruned.edgeAxesTested, full.edgeAxesTested / 4);
}

// Hulls of points on the unit sphere (every point a vertex), as the
// benchmarks use: more edges than the fixtures, so many more Minkowski-face
// pairs per query.
Shape SphereHull(std::mt19937_64& rng, int vertices) {
  std::vector<Vec3> points;
  for (int i = 0; i < vertices; ++i) points.push_back(test::RandomUnit(rng));
  return test::HullShape(points);
}

TEST(SatRandom, PrunedMinkowskiGapsAgreeWithFullProjectionsOnTouchingAndDeepPairs) {
  // The pruned mode measures an edge pair as n . (pB - pA), the full mode
  // by projecting both hulls; both must find the same least overlap. B is
  // slid along u to first contact (brute force), then pushed in by a depth
  // from 1e-4 m (resting contact) to 0.5 m (deep).
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> logDepth(-4.0, std::log10(0.5));
  int edgeContacts = 0;
  for (int vertices : {8, 16, 32}) {
    for (int i = 0; i < 40; ++i) {
      const Shape a = SphereHull(rng, vertices);
      const Shape b = SphereHull(rng, vertices);
      const Transform xfA{.position = Vec3::Zero(), .rotation = test::RandomRotation(rng)};
      Transform xfB{.position = Vec3::Zero(), .rotation = test::RandomRotation(rng)};
      const Vec3 u = test::RandomUnit(rng);
      const double contact = test::BruteSupport(PosedHull::Make(a.GetHull(), xfA), u) +
                             test::BruteSupport(PosedHull::Make(b.GetHull(), xfB), -u);
      xfB.position = u * (contact - std::pow(10.0, logDepth(rng)));
      const Pair p{a, b, xfA, xfB};
      const SatResult f = Sat(p, SatMode::Full);
      const SatResult g = Sat(p, SatMode::GaussMapPruned);
      const double oracle =
          test::BruteMinimumOverlap(PosedHull::Make(a.GetHull(), xfA), PosedHull::Make(b.GetHull(), xfB));
      ASSERT_EQ(f.separated, g.separated);
      ASSERT_EQ(g.separated, oracle < 0.0);
      if (g.separated) continue;
      if (g.axis.type == SatAxisType::EdgePair) ++edgeContacts;
      // Both report one axis measured the same way; round-off only.
      EXPECT_NEAR(f.separation, g.separation, kRoundOff);
      EXPECT_NEAR(-g.separation, oracle, AxisPreferenceBand(p.a.GetHull(), p.b.GetHull()) + kRoundOff);
    }
  }
  EXPECT_GT(edgeContacts, 10);
}

TEST(SatRandom, CrossedTetrahedraEdgesAreMeasuredByTheirGap) {
  // The fixture tetrahedron has a top edge along x = y at z = 1 and a bottom
  // edge along x = -y at z = -1. B, the same tetrahedron lifted by 2 + gap,
  // rests its bottom edge across A's top edge: the pair's distance is `gap`
  // along z, an edge-edge axis only. With a margin above the gap the pair
  // counts as touching and the SAT must report that edge axis and gap; with
  // a margin below it, separated. Both modes: the Full mode meets A's
  // bottom edge x B's top edge first (the same axis and projection gap), so
  // it must find the crossed edges that actually support the axis.
  const Shape tetrahedron = test::HullShape(test::TetrahedronPoints());
  for (const double gap : {1e-4, 1e-2, 0.3}) {
    const Pair p{tetrahedron, tetrahedron, Transform{}, Transform{.position = Vec3(0.0, 0.0, 2.0 + gap)}};
    const PosedHull a = PosedHull::Make(p.a.GetHull(), p.xfA);
    const PosedHull b = PosedHull::Make(p.b.GetHull(), p.xfB);
    for (const SatMode mode : {SatMode::Full, SatMode::GaussMapPruned}) {
      const SatResult touching = RunSat(a, b, mode, 2.0 * gap, nullptr, nullptr);
      ASSERT_FALSE(touching.separated);
      EXPECT_EQ(touching.axis.type, SatAxisType::EdgePair);
      EXPECT_NEAR(touching.separation, gap, kRoundOff) << "mode " << static_cast<int>(mode);
      EXPECT_NEAR((touching.normal - Vec3(0.0, 0.0, -1.0)).norm(), 0.0, kRoundOff);
      EXPECT_TRUE(RunSat(a, b, mode, 0.5 * gap, nullptr, nullptr).separated);
    }
  }
}

TEST(SatRandom, CachedAndUncachedAgreeAlongMotions) {
  std::mt19937_64 rng(6);
  NarrowPhaseStats stats;
  for (int path = 0; path < 60; ++path) {
    const Shape a = test::RandomPolyhedron(rng);
    const Shape b = test::RandomPolyhedron(rng);
    const Vec3 start = test::RandomUnit(rng) * 3.0;
    const Quat spin(Eigen::AngleAxisd(0.02, test::RandomUnit(rng)));
    Transform xfB{.position = start, .rotation = test::RandomRotation(rng)};
    const Transform xfA{.position = Vec3::Zero(), .rotation = test::RandomRotation(rng)};
    SatCache cache;
    // B approaches A through the origin and out again, spinning.
    for (int step = 0; step <= 100; ++step) {
      xfB.position = start * (1.0 - step / 50.0);
      xfB.rotation = (spin * xfB.rotation).normalized();
      const Pair p{a, b, xfA, xfB};
      for (SatMode mode : {SatMode::Full, SatMode::GaussMapPruned}) {
        SatCache modeCache = cache;
        const SatResult cached = Sat(p, mode, &modeCache, &stats);
        const SatResult plain = Sat(p, mode);
        ASSERT_EQ(cached.separated, plain.separated);
        if (!plain.separated) {
          EXPECT_EQ(cached.axis, plain.axis);
          EXPECT_EQ(cached.separation, plain.separation);
        }
        if (mode == SatMode::GaussMapPruned) cache = modeCache;
      }
    }
  }
  EXPECT_GT(stats.satCacheHits, stats.satTests / 4);
}

TEST(SatRandom, OneRigidMotionOfBothChangesOnlyTheFrame) {
  std::mt19937_64 rng(7);
  for (const Pair& p : RandomPairs(8, 800)) {
    const Transform motion{.position = test::RandomUnit(rng) * 5.0, .rotation = test::RandomRotation(rng)};
    const Pair moved{p.a, p.b, motion * p.xfA, motion * p.xfB};
    const SatResult before = Sat(p, SatMode::GaussMapPruned);
    const SatResult after = Sat(moved, SatMode::GaussMapPruned);
    if (std::abs(before.separation) < 1e-9) continue;
    ASSERT_EQ(before.separated, after.separated);
    if (before.separated) continue;
    EXPECT_NEAR(before.separation, after.separation, 1e-10);
    EXPECT_NEAR((motion.Rotate(before.normal) - after.normal).norm(), 0.0, 1e-9);
  }
}

TEST(SatRandom, SwappingAAndBFlipsTheNormalAndNothingElse) {
  const NarrowPhaseSettings settings{.useSatCache = false};
  int compared = 0;
  for (const Pair& p : RandomPairs(9, 1000)) {
    ContactManifold ab{};
    ContactManifold ba{};
    const bool hitAB = Collide(p.a, p.xfA, p.b, p.xfB, settings, nullptr, nullptr, &ab);
    const bool hitBA = Collide(p.b, p.xfB, p.a, p.xfA, settings, nullptr, nullptr, &ba);
    ASSERT_EQ(hitAB, hitBA);
    if (!hitAB) continue;
    EXPECT_NEAR(ab.depth, ba.depth, kRoundOff);
    EXPECT_NEAR((ab.normal + ba.normal).norm(), 0.0, 1e-9);
    // The same points, unless the two faces tie within the preference
    // tolerance and each order picks its own A as the reference.
    if (ab.pointCount != ba.pointCount) continue;
    ++compared;
    for (int i = 0; i < ab.pointCount; ++i) {
      double nearest = 1e300;
      for (int j = 0; j < ba.pointCount; ++j) {
        nearest = std::min(nearest, (ab.points[static_cast<std::size_t>(i)].position -
                                     ba.points[static_cast<std::size_t>(j)].position)
                                        .norm());
      }
      EXPECT_LT(nearest, 1e-9);
    }
  }
  EXPECT_GT(compared, 300);
}

TEST(SatRandom, ClippedPointsLieBetweenTheSurfaces) {
  const NarrowPhaseSettings settings{.manifoldMode = ManifoldMode::Clipped};
  for (const Pair& p : RandomPairs(10, 1500)) {
    ContactManifold m{};
    if (!Collide(p.a, p.xfA, p.b, p.xfB, settings, nullptr, nullptr, &m)) continue;
    ASSERT_GE(m.pointCount, 1);
    ASSERT_LE(m.pointCount, 4);
    EXPECT_NEAR(m.normal.norm(), 1.0, kRoundOff);
    for (int i = 0; i < m.pointCount; ++i) {
      const ContactPoint& c = m.points[static_cast<std::size_t>(i)];
      EXPECT_GE(c.depth, 0.0);
      EXPECT_LE(c.depth, m.depth + 1e-9);
      // Midway: within half the depth of both shapes.
      const double slack = 0.5 * m.depth + 1e-9;
      EXPECT_TRUE(ContainsPoint(p.a.GetHull(), p.xfA.ApplyInverse(c.position), slack));
      EXPECT_TRUE(ContainsPoint(p.b.GetHull(), p.xfB.ApplyInverse(c.position), slack));
    }
  }
}

}  // namespace sat_random_test
}  // namespace talus
