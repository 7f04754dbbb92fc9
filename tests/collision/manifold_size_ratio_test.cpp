// Contact points inside both shapes when one box is 50 to 200 times the
// other's size and their faces are parallel (the SAT check's "scaled"
// family, seed 7, pair 2528: a 1 mm box 0.11 mm into a 12 cm box). The
// small face's corners, clipped out of the large face, lie on its side
// planes to the round-off of the large box's coordinates, ten times the
// small hull's own tolerance; the manifold took every one as beside the
// small box and fell back to a corner of the large face, 5.9 cm outside
// the small box. Checked through the public pair query, against each
// shape's own face planes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "collision/sat_test_fixtures.h"
#include "talus/pair_query.h"

namespace talus {
namespace manifold_size_ratio_test {

using Pair = test::PosedShapes;

double Unit01(std::mt19937_64& rng) { return std::uniform_real_distribution<double>(0.0, 1.0)(rng); }

// Half extents of a box whose largest is `largest`, the others 0.3-1 times it.
Vec3 BoxExtents(std::mt19937_64& rng, double largest) {
  return {largest, largest * (0.3 + 0.7 * Unit01(rng)), largest * (0.3 + 0.7 * Unit01(rng))};
}

// A small box (largest half extent 0.5-2 mm) and a large one (50-200 times
// that), at one random rotation, placed face to face along an axis of that
// rotation so the small face lies inside the large one, overlapping by
// 1e-3 to 0.5 of the small box's half extent along it. Half the pairs put
// the large box first, so both orders of reference face are met.
Pair SizeRatioPair(std::mt19937_64& rng) {
  const Vec3 small = BoxExtents(rng, 5e-4 * std::pow(4.0, Unit01(rng)));
  const Vec3 large = BoxExtents(rng, small.maxCoeff() * 50.0 * std::pow(4.0, Unit01(rng)));
  const Quat rotation = test::RandomRotation(rng);
  const int axis = static_cast<int>(rng() % 3);
  const double sign = rng() % 2 == 0 ? 1.0 : -1.0;
  const Vec3 normal = sign * (rotation * Vec3::Unit(axis));
  const double depth = small[axis] * std::pow(10.0, -3.0 + 2.7 * Unit01(rng));
  // Sideways within the large face, less the small box's reach.
  Vec3 lateralLocal = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    if (k != axis) lateralLocal[k] = (large[k] - small.maxCoeff() * 1.8) * (2.0 * Unit01(rng) - 1.0);
  }
  // Near the origin, as the SAT check's pair was: the small box's world
  // coordinates are then as small as its size, and only the large box's
  // carry the clipped corners' round-off.
  const Vec3 positionSmall =
      small.maxCoeff() * Vec3(2.0 * Unit01(rng) - 1.0, 2.0 * Unit01(rng) - 1.0, 2.0 * Unit01(rng) - 1.0);
  const Vec3 positionLarge =
      positionSmall + normal * (small[axis] + large[axis] - depth) + rotation * lateralLocal;
  const Transform xfSmall{.position = positionSmall, .rotation = rotation};
  const Transform xfLarge{.position = positionLarge, .rotation = rotation};
  if (rng() % 2 == 0) return {test::BoxShape(small), test::BoxShape(large), xfSmall, xfLarge};
  return {test::BoxShape(large), test::BoxShape(small), xfLarge, xfSmall};
}

TEST(ManifoldSizeRatio, EveryClippedPointIsInsideBothShapes) {
  std::mt19937_64 rng(2528);
  std::vector<Pair> pairs;
  for (int i = 0; i < 300; ++i) pairs.push_back(SizeRatioPair(rng));
  for (const SatMode mode : {SatMode::GaussMapPruned, SatMode::Full}) {
    const NarrowPhaseSettings settings{.satMode = mode, .manifoldMode = ManifoldMode::Clipped};
    int outsidePoints = 0;
    int points = 0;
    std::string first;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const Pair& p = pairs[i];
      const Result<PairContact> contact = CollideShapes(p.a, p.xfA, p.b, p.xfB, settings);
      ASSERT_TRUE(contact) << contact.GetError().message;
      const PairContact& c = contact.Value();
      // Every pair overlaps by construction, by at least 1e-3 of the small
      // box: far outside any touching band.
      ASSERT_TRUE(c.touching) << "pair " << i;
      ASSERT_GE(c.pointCount, 1) << "pair " << i;
      for (int k = 0; k < c.pointCount; ++k) {
        const Vec3& x = c.points[static_cast<std::size_t>(k)].position;
        const double outside = std::max(test::OutsideShape(p.a, p.xfA, x), test::OutsideShape(p.b, p.xfB, x));
        ++points;
        if (outside > test::PairRoundOff(p.a, p.xfA, p.b, p.xfB) && outsidePoints++ == 0) {
          std::ostringstream text;
          text << "pair " << i << " point " << k << ": " << outside << " m outside a shape";
          first = text.str();
        }
      }
    }
    EXPECT_EQ(outsidePoints, 0) << outsidePoints << " of " << points << " points; first: " << first;
    // A box face inside a larger parallel face clips to its four corners.
    EXPECT_EQ(points, 4 * static_cast<int>(pairs.size()));
  }
}

}  // namespace manifold_size_ratio_test
}  // namespace talus
