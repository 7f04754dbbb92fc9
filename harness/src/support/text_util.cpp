// The out-of-line helpers of text_util.h: script-safe inlining and file
// reading.
#include "support/text_util.h"

#include <algorithm>
#include <fstream>
#include <sstream>

namespace talus::harness {

std::string ScriptSafe(std::string text) {
  for (std::size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3)) {
    text.replace(at, 2, "<\\/");
  }
  return text;
}

std::string EscapeHtml(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

namespace {

// `byte` written \xNN.
void AppendHexByte(std::string& out, unsigned char byte) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  out.append("\\x").push_back(kHex[byte >> 4]);
  out.push_back(kHex[byte & 0xF]);
}

// Control bytes and the byte-order mark written visibly.
std::string Escape(std::string_view text) {
  static constexpr std::string_view kBom = "\xEF\xBB\xBF";
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if (text.substr(i, kBom.size()) == kBom) {
      out.append("\\uFEFF");
      i += kBom.size() - 1;
    } else if (byte < 0x20 || byte == 0x7F) {
      AppendHexByte(out, byte);
    } else {
      out.push_back(static_cast<char>(byte));
    }
  }
  return out;
}

// The first `limit` bytes of `text`, moved back to a UTF-8 character start.
std::string_view Prefix(std::string_view text, std::size_t limit) {
  std::size_t end = std::min(limit, text.size());
  while (end > 0 && end < text.size() && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80) --end;
  return text.substr(0, end);
}

// `text` with each byte of `marks` written \xNN.
std::string EscapeMarks(std::string_view text, std::string_view marks) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    if (marks.find(c) == std::string_view::npos) {
      out.push_back(c);
    } else {
      AppendHexByte(out, static_cast<unsigned char>(c));
    }
  }
  return out;
}

}  // namespace

std::string TidyMessage(std::string_view message, std::size_t maxQuoted) {
  std::string out;
  std::size_t at = 0;
  while (at < message.size()) {
    // A quote opens at '"', or at "'" after ": " (nlohmann's "last read: '...'");
    // an apostrophe in running text ("box's") opens nothing.
    std::size_t open = at;
    while (open < message.size() && message[open] != '"' &&
           !(message[open] == '\'' && open >= 2 && message.substr(open - 2, 2) == ": ")) {
      ++open;
    }
    if (open >= message.size()) break;
    const std::size_t close = message.find(message[open], open + 1);
    if (close == std::string_view::npos) break;
    const std::string_view inside = message.substr(open + 1, close - open - 1);
    out.append(Escape(message.substr(at, open + 1 - at)));
    if (inside.size() > maxQuoted) {
      // The cut span with its "..." is no longer than maxQuoted, so a message
      // tidied twice reads as one tidied once (Quoted relies on that).
      constexpr std::size_t kCut = 3;
      out.append(Escape(Prefix(inside, maxQuoted > kCut ? maxQuoted - kCut : 0)))
          .append("...")
          .push_back(message[open]);
      out.append(Concat({" (", std::to_string(inside.size()), " bytes)"}));
    } else {
      out.append(Escape(inside)).push_back(message[open]);
    }
    at = close + 1;
  }
  out.append(Escape(message.substr(std::min(at, message.size()))));
  return out;
}

std::string Quoted(std::string_view text, char mark) {
  const std::string_view quote(&mark, 1);
  std::string inside = EscapeMarks(text, quote);
  if (inside.size() <= kMaxQuotedBytes) return Concat({quote, inside, quote});
  // Escapes lengthen the text, so the prefix shrinks until it and "..." fit
  // in kMaxQuotedBytes, which TidyMessage then leaves as it is.
  constexpr std::string_view kCut = "...";
  for (std::size_t keep = kMaxQuotedBytes - kCut.size();; --keep) {
    inside = EscapeMarks(Prefix(text, keep), quote);
    if (inside.size() + kCut.size() <= kMaxQuotedBytes) break;
  }
  return Concat({quote, inside, kCut, quote, " (", std::to_string(text.size()), " bytes)"});
}

std::string PointerForMessage(std::string_view pointer, std::size_t maxBytes) {
  if (pointer.size() <= maxBytes) return EscapeMarks(pointer, "\"'");
  return Concat(
      {EscapeMarks(Prefix(pointer, maxBytes), "\"'"), "... (", std::to_string(pointer.size()), " bytes)"});
}

Result<std::string> ReadTextFile(const std::filesystem::path& path, std::string_view what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{Concat({path.string(), ": cannot read ", what})};
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace talus::harness
