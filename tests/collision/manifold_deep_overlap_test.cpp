// A contact point inside both shapes when the two overlap by more than
// one of them is thick where they meet, so every normal line the manifold
// tries misses their intersection: the incident face's clipped corners,
// its deepest vertex, or the closest points of two edges. The manifold
// then needs another point of the intersection (PointInIntersection in
// polyhedron_manifold.cpp). Two pairs the SAT check found, kept to full
// precision: before, each manifold's one point lay outside a shape, one
// of them 0.45 m outside both.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <vector>

#include "collision/sat_test_fixtures.h"
#include "talus/pair_query.h"

namespace talus {
namespace manifold_deep_overlap_test {

using Pair = test::PosedShapes;

void ExpectEveryPointInsideBoth(const Pair& p) {
  for (const SatMode sat : {SatMode::GaussMapPruned, SatMode::Full}) {
    for (const ManifoldMode manifold : {ManifoldMode::Clipped, ManifoldMode::WriteUp}) {
      const Result<PairContact> contact =
          CollideShapes(p.a, p.xfA, p.b, p.xfB, {.satMode = sat, .manifoldMode = manifold});
      ASSERT_TRUE(contact) << contact.GetError().message;
      const PairContact& c = contact.Value();
      ASSERT_TRUE(c.touching);
      ASSERT_GE(c.pointCount, 1);
      for (int i = 0; i < c.pointCount; ++i) {
        const PairContactPoint& point = c.points[static_cast<std::size_t>(i)];
        const double outside = std::max(test::OutsideShape(p.a, p.xfA, point.position),
                                        test::OutsideShape(p.b, p.xfB, point.position));
        EXPECT_LE(outside, test::PairRoundOff(p.a, p.xfA, p.b, p.xfB))
            << "point " << i << " of " << c.pointCount;
        EXPECT_LE(point.depth, c.Depth() + test::PairRoundOff(p.a, p.xfA, p.b, p.xfB)) << "point " << i;
      }
    }
  }
}

// talus-sat-check --pairs 3000 --seed 10, pair 2940: a box 0.10 m thick
// and an 8-point hull overlapping it by 0.133 m along the box's face.
TEST(ManifoldDeepOverlap, AHullThroughAThinBoxGetsAPointInsideBoth) {
  const Quat rotation(-0.03018026782130297, -0.17463877847445791, 0.78125007161377469, 0.59853051224699938);
  const Pair p{.a = test::BoxShape({0.23340593745611621, 0.050236857310590174, 0.15670606716932517}),
               .b = test::HullShape({{-0.1169922972250691, -0.13885754317873292, 0.061662804570840092},
                                     {-0.20727167947376648, -0.13950446086543586, -0.041999910706806108},
                                     {0.068854859291783047, 0.00248686489837618, -0.082021254889907344},
                                     {0.28966262989223296, 0.10309136434851944, 0.0012378219068855301},
                                     {-0.032658259054072915, 0.21219457714966547, 0.039848283885274012},
                                     {0.26049358350858365, 0.12501981214971897, 0.022536324382079045},
                                     {-0.086341281318105159, -0.045014390053928204, -0.079363407565245736},
                                     {0.14878348269414551, 0.058458725290357866, 0.071557515428114338}}),
               .xfA = {.position = {-0.29408990957176795, -0.57891130464774099, -0.43484460626674892},
                       .rotation = rotation},
               .xfB = {.position = {-0.30134400701119679, -0.56809522454623196, -0.37883257726104236},
                       .rotation = rotation}};
  ExpectEveryPointInsideBoth(p);
}

// talus-sat-check --pairs 3000 --seed 2, pair 2218: an 8-point hull about
// 5 m across 1.6 m into a box 2.6 m thick, faces within 1e-6 rad of
// parallel (the large parallel family).
TEST(ManifoldDeepOverlap, ALargeHullDeepInABoxGetsAPointInsideBoth) {
  const Pair p{.a = test::HullShape({{2.851322393445602, -0.041486300556468993, -0.21453592879805108},
                                     {0.79435109031320716, 0.33030437894020748, 2.201132784883745},
                                     {2.0777402388500077, -0.42405559470447046, 0.16216569974020839},
                                     {-2.5175599478784725, -0.19239727817225788, -1.0004105728028327},
                                     {-1.1505103532138836, 0.49459041196040576, -1.226775137972411},
                                     {1.4847190931690772, 0.15002333466264947, -2.2614366221798448},
                                     {0.62316458861215218, -0.57212651437171247, 0.85026496786590189},
                                     {-1.6965096011933019, 0.30005819739439937, 1.7736392850042526}}),
               .b = test::BoxShape({2.1847808128197799, 1.5907345050759403, 1.2776629085800368}),
               .xfA = {.position = {-0.98304520243052151, 0.27953672267499741, 0.27339590162289262},
                       .rotation = Quat(-0.28604495800606011, 0.89028685680438813, 0.013309155677003859,
                                        -0.35410515525171277)},
               .xfB = {.position = {-0.60548566532892267, 0.7192798909982111, 0.56298562756162251},
                       .rotation = Quat(-0.5098562773688643, -0.76228084311584798, 0.37848602294191025,
                                        0.12539068180599167)}};
  ExpectEveryPointInsideBoth(p);
}

}  // namespace manifold_deep_overlap_test
}  // namespace talus
