// The report's 3D and figure sections (report_html_replay.cpp): the replay
// of runs recorded with --replay, the Quickhull trace (write-up figure 1)
// and the broad-phase funnel per step (figure 2), plus the page status the
// headless-browser test reads. report_html.cpp inserts the whole as one
// block after the charting library and before its own plotting script, and
// puts the replays into the page's data file (kReportDataFile, report.h).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "talus/harness/run/results_file.h"

namespace talus::harness {

/// Which structure ran in a replayed run, counted over its recorded steps
/// from the backend's structure counters (kStructureCounterPrefix):
/// "uniform grid in all 60 recorded steps", or "uniform grid in 58, AABB
/// tree in 2 of 60 recorded steps"; empty when the replay has none.
std::string StructureThatRan(const Replay& replay);

/// The sections' HTML: headings, containers, the Quickhull trace's data,
/// `threeLibrary` (three.js, inlined; empty leaves the 3D views with a
/// message saying so) and scripts. The replays' frames are not in it: the
/// page reads them from kReportReplayFile (ReplayRunsForPage).
std::string ReplaySections(const ResultsFile& file, std::string_view threeLibrary);

/// The replays as the page reads them: per run recorded for replay, its
/// id, bodies and shapes, and per backend its counters and frames in the
/// display form (display_trajectory.h's DisplayReplay: fixed decimal
/// steps far below a pixel; the exact numbers took the default report's
/// replays to 19 MB).
nlohmann::ordered_json ReplayRunsForPage(const ResultsFile& file);

}  // namespace talus::harness
