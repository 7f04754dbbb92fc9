// Persistent contact points (collision/manifold_persistence.h): a box
// tilted on a support box against the exact gaps of its lifted corners,
// points dropped when they separate or slide, and, over random resting
// pairs moved by a few millimetres, the rules (fresh points kept first, at
// most four, every remembered point within the break distance, its two
// surface points on the surfaces to round-off, the deepest point the SAT's
// depth) with the narrow phase as the oracle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>

#include "collision/collide.h"
#include "collision/manifold_persistence.h"
#include "collision/sat_test_fixtures.h"

namespace talus {
namespace manifold_persistence_test {

// Fresh manifolds without a margin, so a lifted corner is not a fresh
// point and only persistence can bring it back.
const NarrowPhaseSettings kSettings{};

constexpr double kBreak = 0.005;  // the default break distance, metres
// The rules for any fresh manifold below four points (the World fills only
// single points, kPersistentFreshPoints; the rules are the same).
constexpr int kAnyFresh = kPersistentMaxPoints - 1;

Quat Turn(const Vec3& axis, double angle) { return Quat(Eigen::AngleAxisd(angle, axis)); }

// A unit cube (half extent 0.5) resting `depth` deep on a 4 x 1 x 4 support
// box whose top face is y = 0.5; A is the support, so the normal is -y.
struct TiltFixture {
  Shape support = test::BoxShape({2.0, 0.5, 2.0});
  Shape cube = test::BoxShape({0.5, 0.5, 0.5});
  Transform xfSupport{};
  Transform xfCube{};
  ContactManifold manifold{};
  ManifoldAnchors anchors{};

  explicit TiltFixture(double depth) {
    xfCube.position = Vec3(0.0, 1.0 - depth, 0.0);
    EXPECT_TRUE(Collide(support, xfSupport, cube, xfCube, kSettings, nullptr, nullptr, &manifold));
    EXPECT_EQ(manifold.pointCount, 4);
    anchors = RecordAnchors(manifold, xfSupport, xfCube);
  }

  // The cube turned by `angle` about its bottom edge at z = -0.5 (parallel
  // to x), lifting its z = +0.5 corners by sin(angle), then moved by
  // `shift`.
  [[nodiscard]] Transform Tilted(double angle, const Vec3& shift) const {
    const Vec3 pivot = xfCube.position + Vec3(0.0, -0.5, -0.5);
    const Quat turn = Turn(Vec3::UnitX(), -angle);
    return {.position = pivot + turn * (xfCube.position - pivot) + shift, .rotation = turn * xfCube.rotation};
  }

  // The fresh manifold at the tilted pose, merged with the remembered one.
  ContactManifold Merged(const Transform& moved, int* added) const {
    ContactManifold fresh{};
    EXPECT_TRUE(Collide(support, xfSupport, cube, moved, kSettings, nullptr, nullptr, &fresh));
    ManifoldAnchors freshAnchors = RecordAnchors(fresh, xfSupport, moved);
    *added =
        MergePersistentPoints(manifold, anchors, xfSupport, moved, kBreak, kAnyFresh, &fresh, &freshAnchors);
    EXPECT_EQ(freshAnchors.pointCount, fresh.pointCount);
    return fresh;
  }
};

TEST(ManifoldPersistence, TiltedBoxKeepsItsLiftedCornersWithTheirExactGaps) {
  const double depth = 0.001;
  const TiltFixture fixture(depth);
  // Lift the far corners by 3 mm: their gap is 2 mm, inside the 5 mm break
  // distance; they slide 1 - cos(angle) = 4.5 um along the surface.
  const double rise = 0.003;
  int added = 0;
  const ContactManifold merged = fixture.Merged(fixture.Tilted(std::asin(rise), Vec3::Zero()), &added);
  ASSERT_EQ(added, 2);
  ASSERT_EQ(merged.pointCount, 4);
  // The fresh points (the near corners, on the turning axis) come first and
  // carry the SAT depth; the remembered far corners have depth - rise.
  // Coordinates of order 1 m through two frame changes: 1e-12 m.
  for (int i = 0; i < 4; ++i) {
    const ContactPoint& p = merged.points[static_cast<std::size_t>(i)];
    const bool far = p.position.z() > 0.0;
    EXPECT_EQ(far, i >= 2) << "point " << i;
    EXPECT_NEAR(p.depth, far ? depth - rise : depth, 1e-12) << "point " << i;
    EXPECT_NEAR(std::abs(p.position.z()), 0.5, 1e-5) << "point " << i;  // drifted 4.5 um at most
  }
  EXPECT_NEAR(merged.depth, depth, 1e-12);
  // The remembered points keep their feature ids (warm starting finds them).
  for (int i = 2; i < 4; ++i) {
    const std::uint32_t id = merged.points[static_cast<std::size_t>(i)].featureId;
    const auto* end = fixture.manifold.points.begin() + fixture.manifold.pointCount;
    EXPECT_NE(std::find_if(fixture.manifold.points.begin(), end,
                           [&](const ContactPoint& p) { return p.featureId == id; }),
              end);
  }
}

TEST(ManifoldPersistence, PointsThatSeparatedOrSlidBeyondTheBreakDistanceAreDropped) {
  const double depth = 0.001;
  const TiltFixture fixture(depth);
  int added = 0;
  // Lifted 7 mm: the far corners are 6 mm clear, beyond 5 mm.
  ContactManifold merged = fixture.Merged(fixture.Tilted(std::asin(depth + 0.006), Vec3::Zero()), &added);
  EXPECT_EQ(added, 0);
  EXPECT_EQ(merged.pointCount, 2);
  // Lifted 3 mm (2 mm clear, kept above) but slid 6 mm along x: the
  // surface points of the far corners are 6 mm apart along the surface.
  merged = fixture.Merged(fixture.Tilted(std::asin(0.003), Vec3(0.006, 0.0, 0.0)), &added);
  EXPECT_EQ(added, 0);
  EXPECT_EQ(merged.pointCount, 2);
  // Slid 4 mm: still within the break distance, kept.
  merged = fixture.Merged(fixture.Tilted(std::asin(0.003), Vec3(0.004, 0.0, 0.0)), &added);
  EXPECT_EQ(added, 2);
  EXPECT_EQ(merged.pointCount, 4);
}

TEST(ManifoldPersistence, FullOrLargerFreshManifoldsAndEmptyHistoriesAreLeftAsTheyAre) {
  const TiltFixture fixture(0.001);
  ContactManifold fresh = fixture.manifold;
  ManifoldAnchors anchors = fixture.anchors;
  EXPECT_EQ(MergePersistentPoints(fixture.manifold, fixture.anchors, fixture.xfSupport, fixture.xfCube,
                                  kBreak, kAnyFresh, &fresh, &anchors),
            0);
  EXPECT_EQ(fresh.pointCount, 4);
  fresh.pointCount = 1;
  anchors.pointCount = 1;
  EXPECT_EQ(MergePersistentPoints(fixture.manifold, ManifoldAnchors{}, fixture.xfSupport, fixture.xfCube,
                                  kBreak, kAnyFresh, &fresh, &anchors),
            0);
  EXPECT_EQ(fresh.pointCount, 1);
  // Two fresh points (the tilted cube's near edge) are more than the
  // World's kPersistentFreshPoints: left as they are; one fresh point (the
  // first of them) is filled with the three other corners.
  const Transform tilted = fixture.Tilted(std::asin(0.003), Vec3::Zero());
  ContactManifold edge{};
  ASSERT_TRUE(
      Collide(fixture.support, fixture.xfSupport, fixture.cube, tilted, kSettings, nullptr, nullptr, &edge));
  ASSERT_EQ(edge.pointCount, 2);
  ManifoldAnchors edgeAnchors = RecordAnchors(edge, fixture.xfSupport, tilted);
  EXPECT_EQ(MergePersistentPoints(fixture.manifold, fixture.anchors, fixture.xfSupport, tilted, kBreak,
                                  kPersistentFreshPoints, &edge, &edgeAnchors),
            0);
  EXPECT_EQ(edge.pointCount, 2);
  edge.pointCount = 1;
  edgeAnchors.pointCount = 1;
  EXPECT_EQ(MergePersistentPoints(fixture.manifold, fixture.anchors, fixture.xfSupport, tilted, kBreak,
                                  kPersistentFreshPoints, &edge, &edgeAnchors),
            3);
  EXPECT_EQ(edge.pointCount, 4);
}

// A contact with a gap is not under load: its single speculative point is
// left alone, while the same point touching is filled (above). The cube of
// the fixture tilted 3 mm on its near edge, then lifted 2 mm: the near edge
// is 1 mm clear of the support (depth -1 mm), so only a speculative margin
// reports it; a 1.5 mm margin takes that edge and not the far corners (2 mm
// clear touching, 4 mm lifted), so the fresh manifold is the edge alone.
// The remembered corners are 1-4 mm clear, inside the 5 mm break distance,
// so nothing but the gap rule keeps them out.
TEST(ManifoldPersistence, ASpeculativeSinglePointIsNotFilled) {
  const double depth = 0.001;
  const TiltFixture fixture(depth);
  const NarrowPhaseSettings margin{.speculativeMargin = 0.0015};
  const double lift = 0.002;
  for (const bool lifted : {false, true}) {
    const Transform moved = fixture.Tilted(std::asin(0.003), Vec3(0.0, lifted ? lift : 0.0, 0.0));
    ContactManifold edge{};
    ASSERT_TRUE(
        Collide(fixture.support, fixture.xfSupport, fixture.cube, moved, margin, nullptr, nullptr, &edge));
    ASSERT_EQ(edge.pointCount, 2) << lifted;
    // Exact to the round-off of order-1 coordinates through a turn.
    EXPECT_NEAR(edge.points[0].depth, lifted ? depth - lift : depth, 1e-12) << lifted;
    edge.pointCount = 1;
    ManifoldAnchors edgeAnchors = RecordAnchors(edge, fixture.xfSupport, moved);
    const int added = MergePersistentPoints(fixture.manifold, fixture.anchors, fixture.xfSupport, moved,
                                            kBreak, kPersistentFreshPoints, &edge, &edgeAnchors);
    EXPECT_EQ(added, lifted ? 0 : 3) << lifted;
    EXPECT_EQ(edge.pointCount, lifted ? 1 : 4) << lifted;
    EXPECT_EQ(edgeAnchors.pointCount, edge.pointCount) << lifted;
  }
}

TEST(ManifoldPersistence, BreakDistanceIsCappedAtOnePercentOfTheSmallerBody) {
  EXPECT_DOUBLE_EQ(PersistentBreakDistance(0.005, 2.0, 0.75), 0.005);
  EXPECT_DOUBLE_EQ(PersistentBreakDistance(0.005, 0.1, 3.0), 0.001);  // a 10 cm body: 1 mm
}

// How far local point `p` lies outside `hull` (metres; <= 0 inside).
double OutsideDistance(const Hull& hull, const Vec3& p) {
  double worst = -std::numeric_limits<double>::infinity();
  for (const HullFace& face : hull.Faces()) worst = std::max(worst, face.plane.SignedDistance(p));
  return worst;
}

// A random hull lying with a random face on a box (or on a random hull's
// face turned up), overlapping by up to 1 cm, then tipped about a
// horizontal axis through one of its contact points by up to 10 mrad
// (millimetres at the hull's far side) and slid by up to 2 mm, in either
// order; the fresh narrow phase at the moved pose is the oracle for the
// points it makes.
Quat FaceTurnedTo(const Hull& hull, int face, const Vec3& direction, double yaw) {
  const Vec3 normal = hull.Faces()[static_cast<std::size_t>(face)].plane.normal;
  return (Turn(Vec3::UnitY(), yaw) * Quat::FromTwoVectors(normal, direction)).normalized();
}

TEST(ManifoldPersistence, RandomRestingPairsObeyTheRules) {
  std::mt19937_64 rng(0x5eed0015);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int mergedPairs = 0;
  int addedPoints = 0;
  double worstOffSurface = 0.0;
  for (int trial = 0; trial < 400; ++trial) {
    const Shape lower = trial % 3 == 0 ? test::RandomPolyhedron(rng) : test::BoxShape({1.0, 0.5, 1.0});
    const Shape upper = test::RandomPolyhedron(rng);
    const auto randomFace = [&](const Shape& s) {
      return static_cast<int>(rng() % static_cast<std::uint64_t>(s.GetHull().FaceCount()));
    };
    const Transform xfLower{.position = Vec3(unit(rng), unit(rng), unit(rng)),
                            .rotation = FaceTurnedTo(lower.GetHull(), randomFace(lower), Vec3::UnitY(),
                                                     2.0 * std::numbers::pi * unit(rng))};
    Transform xfUpper{
        .position = xfLower.position + Vec3(0.2 * (unit(rng) - 0.5), 0.0, 0.2 * (unit(rng) - 0.5)),
        .rotation = FaceTurnedTo(upper.GetHull(), randomFace(upper), -Vec3::UnitY(),
                                 2.0 * std::numbers::pi * unit(rng))};
    // Lowered from above until the two touch, then 0-1 cm further.
    double top = -std::numeric_limits<double>::infinity();
    for (const Vec3& v : lower.GetHull().Vertices()) top = std::max(top, xfLower.Apply(v).y());
    double bottom = std::numeric_limits<double>::infinity();
    for (const Vec3& v : upper.GetHull().Vertices()) bottom = std::min(bottom, xfUpper.Apply(v).y());
    xfUpper.position.y() += top - bottom + 0.002;
    ContactManifold before{};
    for (int k = 0;
         k < 2000 && !Collide(lower, xfLower, upper, xfUpper, kSettings, nullptr, nullptr, &before); ++k)
      xfUpper.position.y() -= 0.001;
    xfUpper.position.y() -= 0.01 * unit(rng);
    const bool swap = trial % 2 == 1;
    const Shape& a = swap ? upper : lower;
    const Shape& b = swap ? lower : upper;
    const Transform xfA = swap ? xfUpper : xfLower;
    const Transform xfB = swap ? xfLower : xfUpper;
    if (!Collide(a, xfA, b, xfB, kSettings, nullptr, nullptr, &before)) continue;
    ManifoldAnchors anchors = RecordAnchors(before, xfA, xfB);
    SnapAnchorsToSurfaces(a, xfA, b, xfB, before, &anchors);

    // Tip B about a horizontal axis through one of the contact points.
    const Vec3 pivot = before.points[rng() % static_cast<std::uint64_t>(before.pointCount)].position;
    const double yawAxis = 2.0 * std::numbers::pi * unit(rng);
    const Quat tip = Turn(Vec3(std::cos(yawAxis), 0.0, std::sin(yawAxis)), 0.01 * unit(rng));
    const Vec3 slide = 0.002 * unit(rng) * Vec3(std::cos(yawAxis), 0.0, -std::sin(yawAxis));
    const Transform movedB{.position = pivot + tip * (xfB.position - pivot) + slide,
                           .rotation = (tip * xfB.rotation).normalized()};
    ContactManifold fresh{};
    if (!Collide(a, xfA, b, movedB, kSettings, nullptr, nullptr, &fresh)) continue;
    const ContactManifold freshOnly = fresh;
    ManifoldAnchors freshAnchors = RecordAnchors(fresh, xfA, movedB);
    SnapAnchorsToSurfaces(a, xfA, b, movedB, fresh, &freshAnchors);
    const int added =
        MergePersistentPoints(before, anchors, xfA, movedB, kBreak, kAnyFresh, &fresh, &freshAnchors);
    ++mergedPairs;
    addedPoints += added;

    ASSERT_EQ(fresh.pointCount, freshOnly.pointCount + added) << "trial " << trial;
    ASSERT_LE(fresh.pointCount, std::max(freshOnly.pointCount, kPersistentMaxPoints));
    // Fresh points first, unchanged; the depth is still the SAT's.
    for (int i = 0; i < freshOnly.pointCount; ++i) {
      const auto k = static_cast<std::size_t>(i);
      EXPECT_EQ(fresh.points[k].position, freshOnly.points[k].position);
      EXPECT_EQ(fresh.points[k].depth, freshOnly.points[k].depth);
    }
    EXPECT_EQ(fresh.depth, freshOnly.depth);
    const double size = SatLengthScale(a.GetHull(), b.GetHull());
    for (int i = freshOnly.pointCount; i < fresh.pointCount; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const ContactPoint& p = fresh.points[k];
      const Vec3 onA = xfA.Apply(freshAnchors.localPointA[k]);
      const Vec3 onB = movedB.Apply(freshAnchors.localPointB[k]);
      // Refreshed from the current poses: midway, depth along the normal.
      EXPECT_LE((p.position - 0.5 * (onA + onB)).norm(), 1e-12 * (1.0 + p.position.norm()));
      EXPECT_NEAR(p.depth, fresh.normal.dot(onB - onA), 1e-12);
      // Within the break distance: not clear by more, not slid by more.
      EXPECT_GE(p.depth, -kBreak);
      EXPECT_LE(((onB - onA) - p.depth * fresh.normal).norm(), kBreak);
      // At least the break distance from every other kept point.
      for (int j = 0; j < fresh.pointCount; ++j) {
        if (j == i) continue;
        EXPECT_GT((p.position - fresh.points[static_cast<std::size_t>(j)].position).norm(), kBreak);
      }
      // No remembered point is deeper than the SAT's least overlap along
      // the normal (for pA in A and pB in B, (pB - pA) . n <= max_B n.x -
      // min_A n.x), so the deepest point stays the fresh one.
      const double roundOff = 1e-9 * size + 1e-12;
      // Its surface points lie on the surfaces of A and B (the features
      // that made the point, met on its normal line: SnapAnchorsToSurfaces)
      // to round-off, at any later pose: they are fixed in the bodies.
      const double off = std::max(std::abs(OutsideDistance(a.GetHull(), xfA.ApplyInverse(onA))),
                                  std::abs(OutsideDistance(b.GetHull(), movedB.ApplyInverse(onB))));
      EXPECT_LE(off, roundOff) << "trial " << trial << " point " << i;
      worstOffSurface = std::max(worstOffSurface, off);
      EXPECT_LE(p.depth, fresh.depth + roundOff) << "trial " << trial;
    }
  }
  // Not vacuous: most pairs touch after the move, and points are added.
  EXPECT_GT(mergedPairs, 200);
  EXPECT_GT(addedPoints, 50);
  std::printf("%d merged pairs, %d remembered points added, surface points at most %.3g m off\n", mergedPairs,
              addedPoints, worstOffSurface);
}

}  // namespace manifold_persistence_test
}  // namespace talus
