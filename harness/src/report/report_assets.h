// The report's own browser scripts as text (generated from
// harness/report/src/*.js by harness/CMakeLists.txt). Owned by
// report_html_replay.cpp; each is plain JavaScript for a <script> element.
#pragma once

namespace talus::harness {

/// status.js: collects errors and writes #report-status when the page loads.
extern const char* const kReportStatusScript;
/// replay.js: the 3D replay, the Quickhull trace and the broad-phase funnel.
extern const char* const kReportReplayScript;

}  // namespace talus::harness
