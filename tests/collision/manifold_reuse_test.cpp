// Manifold reuse (collision/manifold_reuse.h) against the narrow phase as
// the oracle: the motion bound against every vertex's true displacement,
// the rebuilt manifold at the recorded pose against the manifold it came
// from, and, over many random small perturbations of resting pairs (boxes
// and random hulls on boxes), the rebuilt depths against the fresh
// manifold's within the bound derived in the header.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "collision/collide.h"
#include "collision/manifold_reuse.h"
#include "collision/sat_test_fixtures.h"

namespace talus {
namespace manifold_reuse_test {

// The World's narrow-phase choices: clipped manifolds, 2 cm margin.
const NarrowPhaseSettings kSettings{.speculativeMargin = 0.02};

double RadiusAboutOrigin(const Shape& shape) {
  return shape.LocalBoundingSphere().center.norm() + shape.LocalBoundingSphere().radius;
}

// The rigid turn by `angle` about unit `axis`.
Quat Turn(const Vec3& axis, double angle) { return Quat(Eigen::AngleAxisd(angle, axis)); }

// A resting pair: a support box `a` at a random pose and a shape `b` lying
// on the support's top face with one of its faces, at a random yaw and
// lateral offset (sometimes hanging over the edge) and a depth in
// [-5 mm, 1 cm] (speculative to penetrating).
struct RestingPair {
  Shape support;
  Shape top;
  Transform xfSupport;
  Transform xfTop;
};

RestingPair MakeRestingPair(std::mt19937_64& rng, bool randomHull) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Vec3 half(0.6 + 2.0 * unit(rng), 0.5, 0.6 + 2.0 * unit(rng));
  RestingPair pair{.support = test::BoxShape(half),
                   .top = randomHull ? test::RandomPolyhedron(rng)
                                     : test::BoxShape({0.2 + 0.6 * unit(rng), 0.2 + 0.6 * unit(rng),
                                                       0.2 + 0.6 * unit(rng)}),
                   .xfSupport = {.position = 10.0 * Vec3(unit(rng), unit(rng), unit(rng)),
                                 .rotation = test::RandomRotation(rng)},
                   .xfTop = {}};
  // Turn the chosen face of the top shape to face down in the support's
  // frame, then yaw it about the support's up axis.
  const Hull& hull = pair.top.GetHull();
  const int face = static_cast<int>(rng() % static_cast<std::uint64_t>(hull.FaceCount()));
  const Plane& plane = hull.Faces()[static_cast<std::size_t>(face)].plane;
  const Quat down = Quat::FromTwoVectors(plane.normal, -Vec3::UnitY());
  const Quat local = Turn(Vec3::UnitY(), 2.0 * std::numbers::pi * unit(rng)) * down;
  // Turned, the face lies on y = -offset in the top's frame, so the top's
  // origin goes offset above the support's face (y = half.y) less the depth.
  const double depth = -0.005 + 0.015 * unit(rng);
  const Vec3 offset((2.0 * unit(rng) - 1.0) * half.x(), 0.0, (2.0 * unit(rng) - 1.0) * half.z());
  const Vec3 localPosition = offset + Vec3(0.0, half.y() - depth + plane.offset, 0.0);
  pair.xfTop = pair.xfSupport * Transform{.position = localPosition, .rotation = local.normalized()};
  return pair;
}

TEST(ManifoldReuse, MotionBoundHoldsEveryVertexOfBothBodies) {
  std::mt19937_64 rng(0x5eed0001);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 500; ++trial) {
    const Shape a = test::RandomPolyhedron(rng);
    const Shape b = test::RandomPolyhedron(rng);
    const Transform xfA{.position = Vec3(unit(rng), unit(rng), unit(rng)),
                        .rotation = test::RandomRotation(rng)};
    const Transform xfB{.position = Vec3(unit(rng), unit(rng), unit(rng)),
                        .rotation = test::RandomRotation(rng)};
    const ManifoldAnchors anchors = RecordAnchors(
        ContactManifold{.normal = Vec3::UnitY(), .depth = 0.0, .pointCount = 0, .points = {}}, xfA, xfB);
    // Move both bodies by up to a few centimetres and degrees.
    const double scale = std::pow(10.0, -4.0 * unit(rng));
    const Transform movedA{.position = xfA.position + 0.05 * scale * test::RandomUnit(rng),
                           .rotation = Turn(test::RandomUnit(rng), 0.05 * scale * unit(rng)) * xfA.rotation};
    const Transform movedB{.position = xfB.position + 0.05 * scale * test::RandomUnit(rng),
                           .rotation = Turn(test::RandomUnit(rng), 0.05 * scale * unit(rng)) * xfB.rotation};
    const double bound =
        RelativeMotionBound(anchors, movedA, movedB, RadiusAboutOrigin(a), RadiusAboutOrigin(b));
    // The oracle: every vertex of B in A's frame, and of A in B's frame,
    // before and after. Round-off of the frame changes: 1e-12 m.
    double moveB = 0.0;
    for (const Vec3& v : b.GetHull().Vertices()) {
      moveB = std::max(moveB, (movedA.ApplyInverse(movedB.Apply(v)) - xfA.ApplyInverse(xfB.Apply(v))).norm());
    }
    double moveA = 0.0;
    for (const Vec3& v : a.GetHull().Vertices()) {
      moveA = std::max(moveA, (movedB.ApplyInverse(movedA.Apply(v)) - xfB.ApplyInverse(xfA.Apply(v))).norm());
    }
    ASSERT_LE(std::min(moveA, moveB), bound + 1e-12) << "trial " << trial;
    // Not vacuous: the bound is within the slack of the triangle inequality.
    ASSERT_LE(bound, 4.0 * std::min(moveA, moveB) + 1e-12) << "trial " << trial;
  }
}

TEST(ManifoldReuse, NothingRecordedIsNeverCloseEnough) {
  EXPECT_TRUE(std::isinf(RelativeMotionBound(ManifoldAnchors{}, {}, {}, 1.0, 1.0)));
}

TEST(ManifoldReuse, RebuiltAtTheRecordedPoseIsTheNarrowPhaseManifold) {
  std::mt19937_64 rng(0x5eed0002);
  for (int trial = 0; trial < 200; ++trial) {
    const RestingPair pair = MakeRestingPair(rng, trial % 2 == 1);
    ContactManifold fresh{};
    if (!Collide(pair.support, pair.xfSupport, pair.top, pair.xfTop, kSettings, nullptr, nullptr, &fresh))
      continue;
    const ManifoldAnchors anchors = RecordAnchors(fresh, pair.xfSupport, pair.xfTop);
    EXPECT_EQ(RelativeMotionBound(anchors, pair.xfSupport, pair.xfTop, 1.0, 1.0), 0.0);
    ContactManifold rebuilt = fresh;
    RebuildManifold(anchors, pair.xfSupport, pair.xfTop, &rebuilt);
    // Positions of order 10 m through two frame changes: 1e-12 m.
    ASSERT_EQ(rebuilt.pointCount, fresh.pointCount);
    EXPECT_LE((rebuilt.normal - fresh.normal).norm(), 1e-12);
    for (std::size_t i = 0; i < static_cast<std::size_t>(fresh.pointCount); ++i) {
      EXPECT_LE((rebuilt.points[i].position - fresh.points[i].position).norm(), 1e-12) << "trial " << trial;
      EXPECT_NEAR(rebuilt.points[i].depth, fresh.points[i].depth, 1e-12) << "trial " << trial;
      EXPECT_EQ(rebuilt.points[i].featureId, fresh.points[i].featureId);
    }
  }
}

// Perturbs the top body of random resting pairs by a rigid motion that
// moves none of its points by more than delta (1 um to 1 mm: up to the
// default reuse distance), with the pair in either order (A the support or
// A the top, so the reference face is on either side), and compares each
// rebuilt point with the fresh point of the same feature id. The header's
// bound, with phi = theta (the faces start parallel) and the edge-cut length
// L at most the top's or support's diameter plus delta:
//   theta (|depth| + delta) + delta tan(theta) + (2 min(rA, rB) + delta) sin(theta).
void CheckPerturbedRestingPairs(bool randomHull, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int compared = 0;
  int rebuiltPoints = 0;
  double worstRatio = 0.0;
  double worstOverDelta = 0.0;
  for (int trial = 0; trial < 400; ++trial) {
    const RestingPair pair = MakeRestingPair(rng, randomHull);
    const bool supportIsA = trial % 2 == 0;
    const Shape& a = supportIsA ? pair.support : pair.top;
    const Shape& b = supportIsA ? pair.top : pair.support;
    const Transform xfA = supportIsA ? pair.xfSupport : pair.xfTop;
    const Transform xfB = supportIsA ? pair.xfTop : pair.xfSupport;
    ContactManifold recorded{};
    if (!Collide(a, xfA, b, xfB, kSettings, nullptr, nullptr, &recorded)) continue;
    const ManifoldAnchors anchors = RecordAnchors(recorded, xfA, xfB);

    // Turn the top about its origin by theta and shift it by the rest.
    const double rTop = RadiusAboutOrigin(pair.top);
    const double delta = 1e-3 * std::pow(10.0, -3.0 * unit(rng));
    const double share = unit(rng);
    const double theta = share * delta / rTop;
    const Transform moved{
        .position = pair.xfTop.position + (1.0 - share) * delta * test::RandomUnit(rng),
        .rotation = (Turn(test::RandomUnit(rng), theta) * pair.xfTop.rotation).normalized()};
    const Transform nowA = supportIsA ? xfA : moved;
    const Transform nowB = supportIsA ? moved : xfB;
    const double rA = RadiusAboutOrigin(a);
    const double rB = RadiusAboutOrigin(b);
    ASSERT_LE(RelativeMotionBound(anchors, nowA, nowB, rA, rB), delta * (1.0 + 1e-9) + 1e-12);

    ContactManifold fresh{};
    if (!Collide(a, nowA, b, nowB, kSettings, nullptr, nullptr, &fresh)) continue;
    ContactManifold rebuilt = recorded;
    RebuildManifold(anchors, nowA, nowB, &rebuilt);
    rebuiltPoints += rebuilt.pointCount;
    for (std::size_t i = 0; i < static_cast<std::size_t>(rebuilt.pointCount); ++i) {
      for (std::size_t j = 0; j < static_cast<std::size_t>(fresh.pointCount); ++j) {
        if (fresh.points[j].featureId != rebuilt.points[i].featureId) continue;
        const double depth = std::abs(fresh.points[j].depth);
        const double bound = theta * (depth + delta) + delta * std::tan(theta) +
                             (2.0 * std::min(rA, rB) + delta) * std::sin(theta) + 1e-12;
        const double error = std::abs(rebuilt.points[i].depth - fresh.points[j].depth);
        EXPECT_LE(error, bound) << "trial " << trial << " point " << i << " delta " << delta;
        worstRatio = std::max(worstRatio, error / bound);
        worstOverDelta = std::max(worstOverDelta, error / delta);
        ++compared;
      }
    }
  }
  // Most rebuilt points have a fresh twin (a perturbation rarely changes
  // the reference face or the reduction), so the check is not vacuous.
  EXPECT_GE(compared, rebuiltPoints * 3 / 4);
  EXPECT_GE(compared, 500);
  std::printf("%d points compared: worst error / bound %.3g, worst error / delta %.3g\n", compared,
              worstRatio, worstOverDelta);
}

TEST(ManifoldReuse, RebuiltDepthsOfPerturbedRestingBoxesStayWithinTheBound) {
  CheckPerturbedRestingPairs(false, 0x5eed0003);
}

TEST(ManifoldReuse, RebuiltDepthsOfPerturbedRestingHullsStayWithinTheBound) {
  CheckPerturbedRestingPairs(true, 0x5eed0004);
}

}  // namespace manifold_reuse_test
}  // namespace talus
