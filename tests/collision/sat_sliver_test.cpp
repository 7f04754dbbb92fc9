// The Gauss-map pruned SAT on sliver hulls (a cluster of points far
// smaller than the hull, plus a few points far out) against small boxes:
// the shape of the pair_sat fuzz finding
// sliver_hull_gauss_map_separated_while_overlapping, where an edge pair's
// axis was oriented by A's centroid and came out reversed, so an overlap of
// 5 cm was reported as a 5 cm gap. Judged by the brute-force SAT of
// sat_test_fixtures.h, which projects every vertex on every face normal
// and edge cross product and shares no code with the engine's search.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include "collision/sat.h"
#include "collision/sat_test_fixtures.h"
#include "talus/hull_builder.h"

namespace talus {
namespace sat_sliver_test {

// Round-off of one axis measured two ways (projections of coordinates of
// about 1 m): a few thousand ulps.
constexpr double kRoundOff = 1e-12;

// Cases and seed: 3000 pairs take about 0.1 s in Release.
constexpr int kCases = 3000;
constexpr std::uint64_t kSeed = 17;

struct SliverPair {
  std::shared_ptr<const Hull> sliver;
  std::shared_ptr<const Hull> box;
  Transform xfSliver;
  Transform xfBox;
};

// A sliver, the finding's recipe: four points on the corners of a cube of
// side `cluster` (log-uniform from 1e-13 m to 1e-4 m) at the origin, and
// two points up to 0.6 m out near the plane z = 0 (off it by up to 1e-3
// m); null when the builder refuses the set as degenerate. The box, 10 cm
// on a side, sits on the cluster (offset by 0, 1 or 3 cm per axis) with
// its faces parallel to the sliver's frame (identity or a half turn about
// a frame axis): the aligned faces and edges that put the Gauss-map test
// and the axis orientation on their degenerate cases. Each pose also gets
// a random rotation of the whole pair, so the alignment is exact only up
// to round-off.
std::optional<SliverPair> RandomSliverPair(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double cluster = std::pow(10.0, -13.0 + 9.0 * unit(rng));
  std::vector<Vec3> points;
  const auto corner = [&] { return static_cast<double>(rng() % 2) * cluster; };
  for (int i = 0; i < 4; ++i) points.push_back({corner(), corner(), corner()});
  const double lift = std::pow(10.0, -12.0 + 9.0 * unit(rng));
  for (int i = 0; i < 2; ++i)
    points.push_back({1.2 * unit(rng) - 0.6, 1.2 * unit(rng) - 0.6, lift * unit(rng)});
  auto hull = BuildHull(points);
  if (!hull) return std::nullopt;
  SliverPair pair;
  pair.sliver = std::make_shared<const Hull>(std::move(hull).Value());
  pair.box = std::make_shared<const Hull>(Hull::Box(Vec3::Constant(0.05)).Value());
  const Quat frame = test::RandomRotation(rng);
  const Quat halfTurns[] = {Quat::Identity(), Quat(0, 1, 0, 0), Quat(0, 0, 1, 0), Quat(0, 0, 0, 1)};
  const double offsets[] = {0.0, 0.01, -0.01, 0.03, -0.03};
  const auto offset = [&] { return offsets[rng() % 5]; };
  const Vec3 position(unit(rng), unit(rng), unit(rng));
  pair.xfSliver = {.position = position, .rotation = frame};
  pair.xfBox = {.position = position + frame * Vec3(offset(), offset(), offset()),
                .rotation = frame * halfTurns[rng() % 4]};
  return pair;
}

// Runs `check(case, sliverFirst, a, b, oracle, band)` on every random
// sliver pair that builds, in both orders (sliver as A and as B, since the
// edge axis is oriented against A), with the brute-force least overlap
// and the band of the hulls' fitting tolerance plus round-off. Stops at the
// first fatal failure, as an ASSERT in one loop would. Returns the number
// of pairs built.
template <typename Check>
int ForEachRandomSliverPairBothOrders(Check&& check) {
  std::mt19937_64 rng(kSeed);
  int built = 0;
  for (int i = 0; i < kCases && !::testing::Test::HasFatalFailure(); ++i) {
    const auto pair = RandomSliverPair(rng);
    if (!pair) continue;
    ++built;
    const PosedHull sliver = PosedHull::Make(*pair->sliver, pair->xfSliver);
    const PosedHull box = PosedHull::Make(*pair->box, pair->xfBox);
    const double band = pair->sliver->Tolerance() + pair->box->Tolerance() + kRoundOff;
    for (const bool sliverFirst : {true, false}) {
      const PosedHull& a = sliverFirst ? sliver : box;
      const PosedHull& b = sliverFirst ? box : sliver;
      check(i, sliverFirst, a, b, test::BruteMinimumOverlap(a, b), band);
      if (::testing::Test::HasFatalFailure()) break;
    }
  }
  return built;
}

// The brute force and the pruned SAT agree on the verdict (outside the
// touching band of the hulls' tolerances), and whatever axis the SAT
// reports measures, by projection, what the SAT says it does: a
// "separated" answer is never an overlap re-measured.
TEST(SatSliver, PrunedVerdictAndReportedAxisMatchBruteForceOnRandomSlivers) {
  int overlapping = 0;
  const int built = ForEachRandomSliverPairBothOrders(
      [&](int i, bool sliverFirst, const PosedHull& a, const PosedHull& b, double oracle, double band) {
        // Within the hulls' fitting tolerance either verdict is right.
        if (std::abs(oracle) < band) return;
        const SatResult sat = RunSat(a, b, SatMode::GaussMapPruned, 0.0, nullptr, nullptr);
        ASSERT_EQ(sat.separated, oracle < 0.0)
            << "case " << i << (sliverFirst ? " sliver first" : " box first") << ": oracle overlap " << oracle
            << ", SAT separation " << sat.separation;
        // The normal points from B towards A and measures the reported
        // value one-sidedly (B's support along it and A's against it); the
        // two-sided overlap may differ by a sliver's thickness, which the
        // face preference band allows.
        EXPECT_NEAR(test::BruteSupport(b, sat.normal) + test::BruteSupport(a, -sat.normal), -sat.separation,
                    kRoundOff)
            << "case " << i << ", axis type " << static_cast<int>(sat.axis.type);
        if (!sat.separated) ++overlapping;
      });
  // The recipe must exercise both verdicts on many slivers.
  EXPECT_GT(built, 2000);
  EXPECT_GT(overlapping, 1000);
}

// The Full mode's reported overlap on random slivers, both orders, against
// the brute force: never less than the least overlap over all axes (no
// axis overlaps less than the minimum, so a smaller figure is an axis
// measured wrong), and at most the preference band above it (the SAT
// prefers faces within the band). The shape of the fuzz finding
// full_mode_edge_climb_stalled_on_sliver_reported_too_shallow: hill
// climbing stopped on a sliver's round-off-flat edge, so an edge pair's
// gap read too large and its axis beat every correct one (1.7e-4 m too
// shallow in that input).
TEST(SatSliver, FullModeOverlapMatchesBruteForceOnRandomSlivers) {
  int overlapping = 0;
  const int built = ForEachRandomSliverPairBothOrders(
      [&](int i, bool sliverFirst, const PosedHull& a, const PosedHull& b, double oracle, double band) {
        if (oracle < band) return;  // separated, or touching within the hulls' tolerance
        const SatResult sat = RunSat(a, b, SatMode::Full, 0.0, nullptr, nullptr);
        ASSERT_FALSE(sat.separated) << "case " << i << ": oracle overlap " << oracle;
        ++overlapping;
        const double preference = AxisPreferenceBand(*a.hull, *b.hull);
        EXPECT_GE(-sat.separation, oracle - kRoundOff)
            << "case " << i << (sliverFirst ? " sliver first" : " box first") << ", axis type "
            << static_cast<int>(sat.axis.type);
        EXPECT_LE(-sat.separation, oracle + preference + kRoundOff)
            << "case " << i << (sliverFirst ? " sliver first" : " box first") << ", axis type "
            << static_cast<int>(sat.axis.type);
      });
  EXPECT_GT(built, 2000);
  EXPECT_GT(overlapping, 1000);
}

// Every answer is a finite separation along a unit normal, in both modes.
// The supporting edges chosen after the search can be parallel (a sliver
// edge of 2e-11 m next to a box edge), which once gave -inf; 8000 slivers
// of seed 4 include such a pair (case 7067 with this generator).
TEST(SatSliver, SeparationIsFiniteInBothModesOnRandomSlivers) {
  std::mt19937_64 rng(4);
  int built = 0;
  for (int i = 0; i < 8000; ++i) {
    const auto pair = RandomSliverPair(rng);
    if (!pair) continue;
    ++built;
    const PosedHull sliver = PosedHull::Make(*pair->sliver, pair->xfSliver);
    const PosedHull box = PosedHull::Make(*pair->box, pair->xfBox);
    for (const SatMode mode : {SatMode::GaussMapPruned, SatMode::Full}) {
      for (const bool sliverFirst : {true, false}) {
        const SatResult sat = sliverFirst ? RunSat(sliver, box, mode, 0.0, nullptr, nullptr)
                                          : RunSat(box, sliver, mode, 0.0, nullptr, nullptr);
        ASSERT_TRUE(std::isfinite(sat.separation))
            << "case " << i << ", axis type " << static_cast<int>(sat.axis.type);
        // A unit normal: its length is 1 to a few ulps.
        ASSERT_NEAR(sat.normal.norm(), 1.0, 1e-12) << "case " << i;
      }
    }
  }
  EXPECT_GT(built, 5000);
}

}  // namespace sat_sliver_test
}  // namespace talus
