// summary.md's Markdown subset to HTML (markdown_html.h), converted line by
// line: headings with anchors, pipe tables, paragraphs, inline code and links.
#include "report/markdown_html.h"

#include <map>
#include <sstream>
#include <string_view>
#include <vector>

#include "report/report_scorecard.h"
#include "support/text_util.h"

namespace talus::harness {
namespace {

// Markdown links to an anchor of the page, [text](#anchor), become
// <a href="#anchor">text</a>; other brackets stay as they are. The text
// may hold brackets itself (run ids do): it ends at the first "](#".
std::string Links(const std::string& text) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t middle = text[i] == '[' ? text.find("](#", i) : std::string::npos;
    const std::size_t end = middle == std::string::npos ? std::string::npos : text.find(')', middle);
    if (end == std::string::npos) {
      out += text[i++];
      continue;
    }
    out.append("<a href=\"").append(text, middle + 2, end - middle - 2).append("\">");
    out.append(text, i + 1, middle - i - 1).append("</a>");
    i = end + 1;
  }
  return out;
}

// Markdown inline code `x` becomes <code>x</code> (after escaping), and
// links to anchors become links.
std::string Inline(std::string_view text) {
  std::string escaped = Links(EscapeHtml(text));
  std::string out;
  bool open = false;
  for (char c : escaped) {
    if (c == '`') {
      out += open ? "</code>" : "<code>";
      open = !open;
    } else {
      out += c;
    }
  }
  if (open) out += "</code>";
  return out;
}

std::vector<std::string> SplitRow(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  for (std::size_t i = 1; i < line.size(); ++i) {
    if (line[i] == '|') {
      const auto first = cell.find_first_not_of(' ');
      const auto last = cell.find_last_not_of(' ');
      cells.push_back(first == std::string::npos ? std::string() : cell.substr(first, last - first + 1));
      cell.clear();
    } else {
      cell += line[i];
    }
  }
  return cells;
}

}  // namespace

std::string MarkdownToHtml(const std::string& markdown) {
  std::istringstream in(markdown);
  std::ostringstream out;
  std::string line;
  bool inTable = false;
  bool headerRow = false;
  // Heading ids as GitHub makes them: a repeated anchor gets -1, -2...
  std::map<std::string, int> seen;
  const auto id = [&](const std::string& heading) {
    const std::string base = HeadingAnchor(heading);
    const int repeat = seen[base]++;
    return repeat == 0 ? base : Concat({base, "-", std::to_string(repeat)});
  };
  while (std::getline(in, line)) {
    const bool tableLine = !line.empty() && line[0] == '|';
    if (inTable && !tableLine) {
      out << "</table>\n";
      inTable = false;
    }
    if (tableLine) {
      if (line.rfind("|---", 0) == 0) continue;
      if (!inTable) {
        out << "<table>\n";
        inTable = true;
        headerRow = true;
      }
      out << "<tr>";
      for (const std::string& cell : SplitRow(line)) {
        const char* tag = headerRow ? "th" : "td";
        // "FAIL" and "FAIL (ungated)", linked or not: a known failure stays red.
        const bool fail = (cell.size() >= 4 && cell.compare(cell.size() - 4, 4, "FAIL") == 0) ||
                          cell.find(" FAIL (ungated)") != std::string::npos ||
                          cell.find("[FAIL](#") != std::string::npos ||
                          cell.find("[FAIL (ungated)](#") != std::string::npos;
        const bool ok = cell.size() >= 3 && cell.compare(cell.size() - 3, 3, " ok") == 0;
        out << "<" << tag
            << (fail ? " class=\"fail\""
                : ok ? " class=\"ok\""
                     : "")
            << ">" << Inline(cell) << "</" << tag << ">";
      }
      out << "</tr>\n";
      headerRow = false;
    } else if (line.rfind("### ", 0) == 0) {
      out << "<h3 id=\"" << id(line.substr(4)) << "\">" << Inline(line.substr(4)) << "</h3>\n";
    } else if (line.rfind("## ", 0) == 0) {
      // The anchor a FAIL's link points to (the same as GitHub's).
      out << "<h2 id=\"" << id(line.substr(3)) << "\">" << Inline(line.substr(3)) << "</h2>\n";
    } else if (line.rfind("# ", 0) == 0) {
      id(line.substr(2));  // counted, as GitHub counts it
      out << "<h1>" << Inline(line.substr(2)) << "</h1>\n";
    } else if (!line.empty()) {
      out << "<p>" << Inline(line) << "</p>\n";
    }
  }
  if (inTable) out << "</table>\n";
  return out.str();
}

}  // namespace talus::harness
