// Small text helpers shared by the runner, the results file, the readers
// and the report.
// Concat exists because GCC 12 mis-warns (-Wrestrict, a false positive in
// libstdc++'s inlined memcpy at -O3) on chains of std::string operator+
// that start from a literal; appending each piece avoids the pattern.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>

#include "talus/harness/support/number_text.h"
#include "talus/result.h"

namespace talus::harness {

/// The pieces joined in order.
inline std::string Concat(std::initializer_list<std::string_view> pieces) {
  std::string text;
  for (std::string_view piece : pieces) text.append(piece);
  return text;
}

/// `text` with every "</" written "<\\/", so inlined script or JSON cannot
/// end its <script> element early (text_util.cpp).
std::string ScriptSafe(std::string text);

/// `text` as HTML character data or attribute value: & < > " escaped
/// (text_util.cpp). The one escaper of the report's pages.
std::string EscapeHtml(std::string_view text);

/// Longest quoted piece of input a message shows whole (bytes).
inline constexpr std::size_t kMaxQuotedBytes = 64;

/// `message` made safe and short to print: control bytes (NUL included)
/// written \xNN, an invisible byte-order mark written \uFEFF, and every
/// quoted span ("..." or ": '...'") longer than `maxQuoted` bytes cut to its
/// start and "..." (`maxQuoted` bytes in all) and its length ("(4194304
/// bytes)"), never inside a UTF-8 character (text_util.cpp).
std::string TidyMessage(std::string_view message, std::size_t maxQuoted = kMaxQuotedBytes);

/// `text`, a piece of input, between two `mark`s for a message, with every
/// `mark` in it written \xNN, so that TidyMessage pairs the marks as written
/// here whatever the text holds; one longer than kMaxQuotedBytes is cut as
/// TidyMessage cuts it, its length counted in the input's bytes
/// (text_util.cpp).
std::string Quoted(std::string_view text, char mark = '"');

/// A JSON pointer, built from the input's keys, for a message: its quote
/// marks written \x22 and \x27 (TidyMessage would pair them) and one longer
/// than `maxBytes` cut to its start, "...", and its length, as TidyMessage
/// cuts a quoted span (text_util.cpp).
std::string PointerForMessage(std::string_view pointer, std::size_t maxBytes = 128);

/// The whole file as bytes, or an Error "<path>: cannot read <what>"
/// (text_util.cpp).
Result<std::string> ReadTextFile(const std::filesystem::path& path, std::string_view what);

}  // namespace talus::harness
