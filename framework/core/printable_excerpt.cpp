#include "framework/core/printable_excerpt.hpp"

#include <cstdio>

#include "framework/core/control_characters.hpp"
#include "framework/core/utf8_validity.hpp"

namespace crowdlab {

namespace {

/// Bytes of the well-formed UTF-8 character at `i`, or 0 when the byte there does not start one.
std::size_t utf8_character_length(std::string_view s, std::size_t i) {
  const auto b = static_cast<unsigned char>(s[i]);
  const std::size_t length = b < 0x80 ? 1 : b < 0xE0 ? 2 : b < 0xF0 ? 3 : 4;
  if (i + length > s.size()) return 0;
  return first_invalid_utf8_byte(s.substr(i, length)) == std::string_view::npos ? length : 0;
}

void append_escaped_byte(std::string& out, char c) {
  char code[8];
  std::snprintf(code, sizeof code, "\\x%02x", static_cast<unsigned>(static_cast<unsigned char>(c)));
  out += code;
}

std::string more_bytes(std::size_t n) {
  return "... (" + std::to_string(n) + " more bytes)";
}

}  // namespace

std::string printable_excerpt(std::string_view value, std::size_t max_bytes, bool keep_layout) {
  std::string out;
  std::size_t i = 0;
  while (i < value.size() && i < max_bytes) {
    const char c = value[i];
    if (is_control_character(c) && !(keep_layout && (c == '\n' || c == '\t'))) {
      append_escaped_byte(out, c);
      ++i;
      continue;
    }
    const std::size_t length = utf8_character_length(value, i);
    if (length == 0) {
      append_escaped_byte(out, c);
      ++i;
      continue;
    }
    if (i + length > max_bytes) break;  // never cut inside a character
    out.append(value.substr(i, length));
    i += length;
  }
  if (i < value.size()) out += more_bytes(value.size() - i);
  return out;
}

std::string quote_value(std::string_view value) {
  return "'" + printable_excerpt(value, kMaxQuotedBytes) + "'";
}

std::string message_excerpt(std::string_view message) {
  constexpr std::size_t kMaxRun = 400, kMaxMessage = 4000, kHead = 3000, kTail = 500;
  // Cheap exit for the usual short, clean message.
  bool clean = message.size() <= kMaxRun;
  for (char c : message)
    if (!clean || (is_control_character(c) && c != '\n' && c != '\t') ||
        static_cast<unsigned char>(c) >= 0x80) {
      clean = false;
      break;
    }
  if (clean) return std::string(message);
  if (message.size() > kMaxMessage)
    return message_excerpt(message.substr(0, kHead)) + " ... (" +
           std::to_string(message.size() - kHead - kTail) + " bytes left out) ... " +
           message_excerpt(message.substr(message.size() - kTail));
  std::string out;
  std::size_t start = 0;
  while (start < message.size()) {
    std::size_t end = start;
    while (end < message.size() && message[end] != ' ' && message[end] != '\n') ++end;
    out += printable_excerpt(message.substr(start, end - start), kMaxRun, /*keep_layout=*/true);
    if (end < message.size()) out += message[end];
    start = end + 1;
  }
  return out;
}

}  // namespace crowdlab
