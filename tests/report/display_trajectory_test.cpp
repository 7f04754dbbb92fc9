// The display form of the trajectories (display_trajectory.h): what the
// trajectory file holds by default and the page draws. Each bound below is
// the rounding step the header states, halved (round to nearest), with a
// reason beside it; the metrics never see this form (runner.cpp computes
// them from the full trajectory).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "talus/harness/run/display_trajectory.h"
#include "talus/harness/support/split_mix64.h"

namespace talus::harness {
namespace display_trajectory_test {

TEST(DisplayTrajectory, RoundsToTheDecimalItsJsonWritesShortest) {
  // The nearest double to the decimal, so nlohmann's shortest round-trip
  // form prints the decimal itself.
  EXPECT_EQ(RoundToDecimals(0.123456789, 4), 0.1235);
  EXPECT_EQ(RoundToDecimals(-2.00004, 4), -2.0);
  EXPECT_EQ(RoundToDecimals(1.0 / 240 * 7, 6), 0.029167);
  EXPECT_EQ(RoundToDecimals(-0.00001, 3), 0.0);
  EXPECT_FALSE(std::signbit(RoundToDecimals(-0.00001, 3)));  // no "-0" in the files
  EXPECT_TRUE(std::isnan(RoundToDecimals(NAN, 4)));
  EXPECT_EQ(RoundToDecimals(INFINITY, 4), INFINITY);
  EXPECT_EQ(RoundToDecimals(1e300, 4), 1e300);  // past 2^53 nothing is left to round
}

// A series of `points` samples of a bouncing height over 3 s, plus noise in
// the last digits (what an engine's doubles look like).
PlotSeries Bouncing(int points, std::uint64_t seed) {
  SplitMix64 random(seed);
  PlotSeries s;
  s.heights.resize(2);
  for (int i = 0; i < points; ++i) {
    const double t = 3.0 * i / (points - 1);
    s.time.push_back(t);
    s.heights[0].push_back(0.5 + std::abs(std::sin(4.0 * t)) * std::exp(-t) + 1e-9 * random.NextUniform());
    s.heights[1].push_back(0.25);  // a body at rest: not drawn by the page
    s.energy.push_back(9.81 * s.heights[0].back() + 1e-6 * random.NextUniform());
  }
  return s;
}

TEST(DisplayTrajectory, SeriesKeepFirstAndLastAndStayWithinHalfAStepOfTheirRange) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const PlotSeries full = Bouncing(200, seed);
    const PlotSeries shown = DisplaySeries(full);
    ASSERT_EQ(shown.time.size(), static_cast<std::size_t>(kDisplayPlotPoints));
    ASSERT_EQ(shown.energy.size(), shown.time.size());
    ASSERT_EQ(shown.heights[0].size(), shown.time.size());
    EXPECT_EQ(shown.time.front(), 0.0);
    EXPECT_EQ(shown.time.back(), 3.0);
    // Each kept point is one of the recorded ones, rounded: within half the
    // series' step, which is at most kDisplaySeriesResolution of its range
    // (under half a pixel of a 350 px plot).
    const auto range = [](const std::vector<double>& v) {
      return *std::max_element(v.begin(), v.end()) - *std::min_element(v.begin(), v.end());
    };
    const double heightTolerance = 0.5 * kDisplaySeriesResolution * range(full.heights[0]);
    const double energyTolerance = 0.5 * kDisplaySeriesResolution * range(full.energy);
    for (std::size_t i = 0; i < shown.time.size(); ++i) {
      const auto at = std::find_if(full.time.begin(), full.time.end(),
                                   [&](double t) { return std::abs(t - shown.time[i]) <= 0.5e-6; });
      ASSERT_NE(at, full.time.end()) << "point " << i << " is not a recorded time";
      const std::size_t k = static_cast<std::size_t>(at - full.time.begin());
      EXPECT_LE(std::abs(shown.heights[0][i] - full.heights[0][k]), heightTolerance) << "seed " << seed;
      EXPECT_LE(std::abs(shown.energy[i] - full.energy[k]), energyTolerance) << "seed " << seed;
      EXPECT_EQ(shown.heights[1][i], 0.25);  // a constant series is kept as it is
    }
  }
}

TEST(DisplayTrajectory, ReplayKeepsEveryFrameWithinTheStatedSteps) {
  SplitMix64 random(7);
  Replay full;
  full.counterNames = {"contact points"};
  for (int f = 0; f < 50; ++f) {
    ReplayFrame frame;
    frame.time = f / 240.0;
    const Quat q = Quat(random.NextUniform() - 0.5, random.NextUniform() - 0.5, random.NextUniform() - 0.5,
                        random.NextUniform() - 0.5)
                       .normalized();
    frame.positions = {Vec3(random.NextUniform(), random.NextUniform(), random.NextUniform()) * 4.0};
    frame.orientations = {q};
    frame.contacts = {{0, 1, Vec3(random.NextUniform(), 0.0, random.NextUniform()),
                       Vec3(random.NextUniform(), 1.0, random.NextUniform()).normalized(),
                       1e-3 * random.NextUniform()}};
    frame.counters = {4.0};
    full.frames.push_back(frame);
  }
  const Replay shown = DisplayReplay(full);
  ASSERT_EQ(shown.frames.size(), full.frames.size());
  for (std::size_t f = 0; f < full.frames.size(); ++f) {
    const ReplayFrame& a = full.frames[f];
    const ReplayFrame& b = shown.frames[f];
    EXPECT_LE(std::abs(a.time - b.time), 0.5e-6);                                // 1e-6 s steps
    EXPECT_LE((a.positions[0] - b.positions[0]).cwiseAbs().maxCoeff(), 0.5e-4);  // 0.1 mm steps
    EXPECT_LE((a.orientations[0].coeffs() - b.orientations[0].coeffs()).cwiseAbs().maxCoeff(), 0.5e-4);
    EXPECT_LE((a.contacts[0].point - b.contacts[0].point).cwiseAbs().maxCoeff(), 0.5e-4);
    EXPECT_LE((a.contacts[0].normal - b.contacts[0].normal).cwiseAbs().maxCoeff(), 0.5e-3);
    EXPECT_LE(std::abs(a.contacts[0].depth - b.contacts[0].depth), 0.5e-5);
    EXPECT_EQ(b.contacts[0].bodyA, 0);
    EXPECT_EQ(b.contacts[0].bodyB, 1);
    EXPECT_EQ(b.counters, a.counters);  // counts are exact
  }
}

}  // namespace display_trajectory_test
}  // namespace talus::harness
