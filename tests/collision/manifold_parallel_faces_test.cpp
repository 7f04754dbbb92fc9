// Contact points inside both shapes on the class issue 26 found: large
// hulls (about 5 m across) placed face to face with the two faces turned
// 1e-8 to 1e-6 rad from parallel. The SAT may then keep either face inside
// its 1e-7 preference band, and the incident vertex that measures the
// depth can lie beside the reference face; an independent qhull check
// found clipped points up to 1.1 m outside one shape there. Checked
// through the public pair query, against each shape's own face planes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "collision/sat.h"
#include "collision/sat_test_fixtures.h"
#include "talus/pair_query.h"

namespace talus {
namespace manifold_parallel_faces_test {

struct Pair : test::PosedShapes {
  double twist = 0.0;  // radians between the two faces
};

double Unit01(std::mt19937_64& rng) { return std::uniform_real_distribution<double>(0.0, 1.0)(rng); }

// A box or a hull of 8-64 points on an ellipsoid and its six poles; largest half extent
// 2-3 m, the others 0.4-1 times that (5 m across, as in the issue).
Shape LargeShape(std::mt19937_64& rng) {
  const double largest = 2.0 + Unit01(rng);
  const Vec3 extents(largest, largest * (0.4 + 0.6 * Unit01(rng)), largest * (0.4 + 0.6 * Unit01(rng)));
  if (rng() % 3 == 0) return test::BoxShape(extents);
  // The six poles, so the hull spans its extents, then 8-64 more points.
  std::vector<Vec3> points;
  for (int axis = 0; axis < 3; ++axis) {
    points.push_back(extents[axis] * Vec3::Unit(axis));
    points.push_back(-extents[axis] * Vec3::Unit(axis));
  }
  const int count = 8 << (rng() % 4);
  for (int i = 0; i < count; ++i) points.push_back(test::RandomUnit(rng).cwiseProduct(extents));
  return test::HullShape(points);
}

double SupportAlong(const Shape& shape, const Quat& rotation, const Vec3& direction) {
  return direction.dot(rotation * shape.Support(rotation.conjugate() * direction));
}

// A face of B turned to face a face of A, then twisted by 10^U(-8, -6) rad
// about a random axis; B placed against that face, overlapping along it by
// 1e-9 to 1e-2 of the size (or just apart, within 1e-9 of it), and moved
// sideways up to 0.6 of the size, so the faces overlap only in part.
Pair NearlyParallelPair(std::mt19937_64& rng) {
  Pair p{{LargeShape(rng), LargeShape(rng), {}, {}}};
  const Quat rotationA = test::RandomRotation(rng);
  const auto facesA = p.a.GetHull().Faces();
  const auto facesB = p.b.GetHull().Faces();
  const Vec3 normalA = rotationA * facesA[rng() % facesA.size()].plane.normal;
  const Vec3 normalB = facesB[rng() % facesB.size()].plane.normal;
  // B's face normal onto -normalA, then a random spin about normalA.
  const Quat align = Quat::FromTwoVectors(normalB, -normalA);
  const Quat spin(Eigen::AngleAxisd(2.0 * 3.141592653589793 * Unit01(rng), normalA));
  p.twist = std::pow(10.0, -8.0 + 2.0 * Unit01(rng));
  const Quat rotationB =
      (Quat(Eigen::AngleAxisd(p.twist, test::RandomUnit(rng))) * spin * align).normalized();
  const double size = std::min(p.a.LocalAabb().max.maxCoeff(), p.b.LocalAabb().max.maxCoeff());
  const double gap = rng() % 4 == 0 ? size * (2.0 * Unit01(rng) - 1.0) * 1e-9
                                    : -size * std::pow(10.0, -9.0 + 7.0 * Unit01(rng));
  Vec3 lateral = test::RandomUnit(rng);
  lateral -= normalA * normalA.dot(lateral);
  lateral *= 0.6 * size * Unit01(rng);
  // Along normalA, A's extent (towards B) and B's (towards A) meet at gap 0.
  const double reach = SupportAlong(p.a, rotationA, normalA) + SupportAlong(p.b, rotationB, -normalA);
  const Vec3 positionA(Unit01(rng) - 0.5, Unit01(rng) - 0.5, Unit01(rng) - 0.5);
  p.xfA = {.position = positionA, .rotation = rotationA};
  p.xfB = {.position = positionA + normalA * (reach + gap) + lateral, .rotation = rotationB};
  return p;
}

struct Tally {
  int touching = 0;
  int points = 0;
  int outside = 0;
  int shallower = 0;  // pairs whose deepest point is shallower than the depth
  double worst = 0.0;
  std::string first;
};

void CheckPoints(const Pair& p, int index, const NarrowPhaseSettings& settings, Tally* tally) {
  const Result<PairContact> contact = CollideShapes(p.a, p.xfA, p.b, p.xfB, settings);
  ASSERT_TRUE(contact) << contact.GetError().message;
  const PairContact& c = contact.Value();
  if (!c.touching) return;
  ++tally->touching;
  ASSERT_GE(c.pointCount, 1) << "pair " << index;
  const double bound = test::PairRoundOff(p.a, p.xfA, p.b, p.xfB);
  double deepest = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < c.pointCount; ++i) {
    const PairContactPoint& point = c.points[static_cast<std::size_t>(i)];
    deepest = std::max(deepest, point.depth);
    ++tally->points;
    const double outside = std::max(test::OutsideShape(p.a, p.xfA, point.position),
                                    test::OutsideShape(p.b, p.xfB, point.position));
    if (outside > bound) {
      if (tally->outside++ == 0) {
        std::ostringstream text;
        text << "pair " << index << " (twist " << p.twist << " rad) point " << i << " of " << c.pointCount
             << ": " << outside << " m outside a shape, bound " << bound;
        tally->first = text.str();
      }
      tally->worst = std::max(tally->worst, outside);
    }
  }
  // No point is deeper than the reported depth (pair_query.h: the deepest
  // vertex beside the reference face may be out of contact, so the points
  // can be shallower), and the depth is the least overlap over every axis
  // (brute force, sharing no code with the SAT), up to the SAT's
  // preference band.
  EXPECT_LE(deepest, c.Depth() + bound) << "pair " << index;
  if (deepest < c.Depth() - bound) ++tally->shallower;
  const double oracle =
      test::BruteMinimumOverlap(PosedHull::Make(p.a.GetHull(), p.xfA), PosedHull::Make(p.b.GetHull(), p.xfB));
  EXPECT_GE(c.Depth(), oracle - bound) << "pair " << index;
  EXPECT_LE(c.Depth(), oracle + AxisPreferenceBand(p.a.GetHull(), p.b.GetHull()) + bound) << "pair " << index;
}

std::vector<Pair> Pairs(std::uint64_t seed, int count) {
  std::mt19937_64 rng(seed);
  std::vector<Pair> pairs;
  for (int i = 0; i < count; ++i) pairs.push_back(NearlyParallelPair(rng));
  return pairs;
}

// 400 pairs: the failures were 56 of 200 of this class.
TEST(ManifoldParallelFaces, EveryClippedPointIsInsideBothShapes) {
  const std::vector<Pair> pairs = Pairs(26, 400);
  for (const SatMode mode : {SatMode::GaussMapPruned, SatMode::Full}) {
    Tally tally;
    const NarrowPhaseSettings settings{.satMode = mode, .manifoldMode = ManifoldMode::Clipped};
    for (std::size_t i = 0; i < pairs.size(); ++i)
      CheckPoints(pairs[i], static_cast<int>(i), settings, &tally);
    // Most pairs overlap by construction; a quarter are within 1e-9 of
    // touching and go either way, and a small face of a round hull moved
    // sideways can miss the other face (217 of 400 touch).
    EXPECT_GE(tally.touching, 200);
    EXPECT_EQ(tally.outside, 0) << tally.outside << " of " << tally.points << " points (" << tally.shallower
                                << " pairs with every point shallower than the depth), worst " << tally.worst
                                << " m; first: " << tally.first;
  }
}

// The class really is what the issue names: twists span 1e-8 to 1e-6 rad,
// and the shapes are about 5 m across.
TEST(ManifoldParallelFaces, PairsSpanTheTwistsAndSizesAsked) {
  const std::vector<Pair> pairs = Pairs(26, 400);
  double smallest = 1.0;
  double largest = 0.0;
  for (const Pair& p : pairs) {
    smallest = std::min(smallest, p.twist);
    largest = std::max(largest, p.twist);
    EXPECT_GE(2.0 * p.a.LocalAabb().max.maxCoeff(), 4.0);
    EXPECT_GE(2.0 * p.b.LocalAabb().max.maxCoeff(), 4.0);
  }
  EXPECT_LT(smallest, 2e-8);
  EXPECT_GT(largest, 5e-7);
}

}  // namespace manifold_parallel_faces_test
}  // namespace talus
