// The display form of a run's trajectories (see display_trajectory.h).
#include "talus/harness/run/display_trajectory.h"

#include <algorithm>
#include <cmath>

#include "talus/harness/backend/trajectory.h"

namespace talus::harness {
namespace {

// Decimal places that resolve kDisplaySeriesResolution of the finite
// values' range; a constant series (which the page does not draw) keeps
// the finest places, so nothing about it changes.
int SeriesDecimals(const std::vector<double>& values) {
  double low = INFINITY, high = -INFINITY;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    low = std::min(low, v);
    high = std::max(high, v);
  }
  if (!(high > low)) return 15;
  const double step = (high - low) * kDisplaySeriesResolution;
  return std::clamp(static_cast<int>(std::ceil(-std::log10(step))), 0, 15);
}

std::vector<double> Rounded(const std::vector<double>& values, int decimals) {
  std::vector<double> out;
  out.reserve(values.size());
  for (double v : values) out.push_back(RoundToDecimals(v, decimals));
  return out;
}

Vec3 Rounded(const Vec3& v, int decimals) {
  return {RoundToDecimals(v.x(), decimals), RoundToDecimals(v.y(), decimals),
          RoundToDecimals(v.z(), decimals)};
}

}  // namespace

double RoundToDecimals(double value, int decimals) {
  if (!std::isfinite(value)) return value;
  const double scale = std::pow(10.0, decimals);
  const double scaled = value * scale;
  // Beyond 2^53 a double holds only integers: nothing is left to round.
  if (!(std::abs(scaled) < 9007199254740992.0)) return value;
  // An integer over an exact power of ten: the division is correctly
  // rounded, so the result is the double nearest the decimal.
  const double rounded = std::round(scaled) / scale;
  return rounded == 0.0 ? 0.0 : rounded;  // no "-0" in the files
}

PlotSeries DisplaySeries(const PlotSeries& series) {
  const std::vector<std::size_t> keep =
      SpreadIndices(series.time.size(), static_cast<std::size_t>(kDisplayPlotPoints));
  const auto thinned = [&keep](const std::vector<double>& values) {
    std::vector<double> out;
    for (std::size_t index : keep) {
      if (index < values.size()) out.push_back(values[index]);
    }
    return out;
  };
  PlotSeries out;
  out.time = Rounded(thinned(series.time), kDisplayTimeDecimals);
  const std::vector<double> energy = thinned(series.energy);
  out.energy = Rounded(energy, SeriesDecimals(energy));
  for (const std::vector<double>& heights : series.heights) {
    const std::vector<double> h = thinned(heights);
    out.heights.push_back(Rounded(h, SeriesDecimals(h)));
  }
  return out;
}

Replay DisplayReplay(const Replay& replay) {
  Replay out = replay;
  for (ReplayFrame& frame : out.frames) {
    frame.time = RoundToDecimals(frame.time, kDisplayTimeDecimals);
    for (Vec3& p : frame.positions) p = Rounded(p, kDisplayPositionDecimals);
    for (Quat& q : frame.orientations) {
      q = Quat(RoundToDecimals(q.w(), kDisplayQuaternionDecimals),
               RoundToDecimals(q.x(), kDisplayQuaternionDecimals),
               RoundToDecimals(q.y(), kDisplayQuaternionDecimals),
               RoundToDecimals(q.z(), kDisplayQuaternionDecimals));
    }
    for (ContactReading& c : frame.contacts) {
      c.point = Rounded(c.point, kDisplayPositionDecimals);
      c.normal = Rounded(c.normal, kDisplayNormalDecimals);
      c.depth = RoundToDecimals(c.depth, kDisplayDepthDecimals);
    }
  }
  return out;
}

}  // namespace talus::harness
