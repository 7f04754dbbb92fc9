// Scenario text to a JSON document (scenario_json_text.h): nlohmann's
// syntax errors placed by line and column with the input it quotes
// re-quoted, and the nesting bounded.
#include "scenario/scenario_json_text.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "support/text_util.h"
#include "talus/harness/scenario/scenario_limits.h"

namespace talus::harness {
namespace {

using nlohmann::json;

// Line and column (both from 1) of byte `offset` in `text`.
std::string LineAndColumn(std::string_view text, size_t offset) {
  size_t line = 1;
  size_t column = 1;
  for (size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// Deepest nesting of `doc`, walked with an explicit stack (the document may
// be nested deeper than the call stack allows); stops counting past `limit`.
int NestingDepth(const json& doc, int limit) {
  int deepest = 0;
  std::vector<std::pair<const json*, int>> pending{{&doc, 0}};
  while (!pending.empty()) {
    const auto [value, depth] = pending.back();
    pending.pop_back();
    deepest = std::max(deepest, depth);
    if (deepest > limit) return deepest;
    if (value->is_structured()) {
      for (const json& child : *value) pending.emplace_back(&child, depth + 1);
    }
  }
  return deepest;
}

// nlohmann's syntax error reads "<reason>; last read: '<token>'" and then,
// when it knows one, "; expected <kind of token>". The reason and the kind
// are its own fixed words; the token is the input as read, of any length and
// holding any quote marks, which left TidyMessage pairing the wrong marks and
// printing kilobytes of input (a fuzz finding, tests/data/fuzz/scenario_loader).
// The token is quoted again here with its own marks escaped.
std::string RequoteLastRead(const std::string& what) {
  static constexpr std::string_view kLastRead = "; last read: '";
  // lexer::token_type_name, every kind nlohmann may name as expected.
  static constexpr std::string_view kTokenKinds[] = {"<uninitialized>",
                                                     "true literal",
                                                     "false literal",
                                                     "null literal",
                                                     "string literal",
                                                     "number literal",
                                                     "'['",
                                                     "'{'",
                                                     "']'",
                                                     "'}'",
                                                     "':'",
                                                     "','",
                                                     "<parse error>",
                                                     "end of input",
                                                     "'[', '{', or a literal",
                                                     "unknown token"};
  const size_t start = what.find(kLastRead);
  if (start == std::string::npos) return what;
  std::string_view token = std::string_view(what).substr(start + kLastRead.size());
  std::string expected;
  for (const std::string_view kind : kTokenKinds) {
    const std::string tail = Concat({"'; expected ", kind});
    if (token.ends_with(tail)) {
      expected = tail.substr(1);
      token.remove_suffix(tail.size());
      break;
    }
  }
  if (expected.empty()) {
    if (!token.ends_with('\'')) return what;
    token.remove_suffix(1);
  }
  return Concat({std::string_view(what).substr(0, start), "; last read: ", Quoted(token, '\''), expected});
}

// nlohmann's syntax error as the loader reports it: file, line and column,
// then nlohmann's words with the input it quotes re-quoted.
Error SyntaxError(const json::parse_error& error, std::string_view text, std::string_view fileName) {
  // nlohmann's byte is one past the last character of the offending token.
  const size_t offset = error.byte > 0 ? error.byte - 1 : 0;
  std::string what = error.what();
  const size_t colon = what.find(": ");
  if (colon != std::string::npos) what = what.substr(colon + 2);
  return Error{Concat({fileName, ": ", LineAndColumn(text, offset), ": ", RequoteLastRead(what)})};
}

}  // namespace

Result<nlohmann::json> ParseScenarioJson(std::string_view text, std::string_view fileName) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& error) {
    return SyntaxError(error, text, fileName);
  } catch (const json::exception& error) {
    // A number too large for a double (e.g. 1e999) has no position.
    std::string what = error.what();
    const size_t bracket = what.find("] ");
    if (bracket != std::string::npos) what = what.substr(bracket + 2);
    return Error{std::string(fileName) + ": " + what};
  }
  if (NestingDepth(doc, kMaxJsonDepth) > kMaxJsonDepth) {
    return Error{Concat({fileName, ": nested more than ", std::to_string(kMaxJsonDepth),
                         " arrays or objects deep (the limit)"})};
  }
  return doc;
}

}  // namespace talus::harness
