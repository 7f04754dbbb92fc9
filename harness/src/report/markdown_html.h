// MarkdownToHtml: summary.md's Markdown subset as HTML, so report.html's
// tables are summary.md's and the two never disagree.
#pragma once

#include <string>

namespace talus::harness {

/// HTML for summary.md's Markdown subset: headings (#, ##, ###; each with
/// the anchor id of report_scorecard.h's HeadingAnchor), pipe tables
/// (cells ending in FAIL / ok coloured), paragraphs, `code`.
std::string MarkdownToHtml(const std::string& markdown);

}  // namespace talus::harness
