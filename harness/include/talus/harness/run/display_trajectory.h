// The trajectories as the report draws them: the form results.trajectories.json
// holds by default and the page's data files always hold.
//
// The runner computes every metric and verdict from the full trajectory
// before any of this (runner.cpp); only what is written for display is
// thinned and rounded. The limits are what the eye can tell apart, stated
// with their reasons beside the constants below; the bytes per run they
// give are measured in docs/testbed-report.md ("Sizes"). A run keeps the
// exact form with `talus-testbed run --full-trajectories`.
#pragma once

#include "talus/harness/run/replay.h"
#include "talus/harness/run/runner.h"

namespace talus::harness {

/// Most points of each plotted series. A plot is about 700 px wide, so 50
/// points put a vertex every 14 px: a line drawn through them follows the
/// 200-point one within a few pixels on the smooth stretches and rounds
/// the corners of impacts within one point's span (2% of the run). 100
/// points (every 7 px) took the series over the 5 MB budget once the suite
/// grew to 36 files (docs/testbed-report.md, "Sizes").
inline constexpr int kDisplayPlotPoints = 50;

/// A plotted value is rounded to a decimal step at most this fraction of
/// its own series' range (max - min): the plot scales its axis to the
/// data, about 350 px high, so 1/1000 of the range is under half a pixel.
inline constexpr double kDisplaySeriesResolution = 1e-3;

/// Decimal places kept in a replay (all fixed steps, so a body at rest
/// stays exactly at rest in the drawing):
///   time 1e-6 s: the page prints t to 1e-3 s and frames are at least one
///     step (>= 1e-4 s in the suite) apart;
///   positions and contact points 1e-4 m: a replay viewport is 320 px high
///     over a scene of metres (~3 mm a pixel), 30 times coarser;
///   quaternion components 1e-4: at most about 2e-4 rad of rotation
///     (0.01 degree), a 1 m box's corner moving 0.2 mm;
///   normals 1e-3: about 0.06 degree; they are drawn as short lines;
///   depth 1e-5 m: 0.01 mm, 400 times below the 4 mm slop; not drawn.
/// Step counters are counts and kept exact.
inline constexpr int kDisplayTimeDecimals = 6;
inline constexpr int kDisplayPositionDecimals = 4;
inline constexpr int kDisplayQuaternionDecimals = 4;
inline constexpr int kDisplayNormalDecimals = 3;
inline constexpr int kDisplayDepthDecimals = 5;

/// `value` rounded to `decimals` decimal places (0..15); the result is the
/// double nearest that decimal, so JSON writes it with at most that many
/// places. Non-finite values are returned unchanged.
double RoundToDecimals(double value, int decimals);

/// `series` thinned to kDisplayPlotPoints evenly spread points (first and
/// last kept) and each series rounded by kDisplaySeriesResolution of its
/// range (time to kDisplayTimeDecimals).
PlotSeries DisplaySeries(const PlotSeries& series);

/// `replay` with every frame kept and its numbers rounded as above.
Replay DisplayReplay(const Replay& replay);

}  // namespace talus::harness
