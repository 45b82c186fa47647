#pragma once
// What an error message may echo of a user's bytes (issue 33). Messages quoted whole values: a 50 MB CSV
// line, 30,000 brackets from a glTF field, raw binary from a BVH file filled or corrupted the terminal. One
// helper makes any value safe to print: control bytes (0x00-0x1f, 0x7f, ECMA-6) and bytes that are not
// well-formed UTF-8 (Unicode 15, Table 3-7) become \xNN escapes, and the value is cut at a byte budget with
// the count of what was left out. InputError applies message_excerpt() to every message it carries, so no
// call site can forget it; quote_value() is for the values call sites put in quotes themselves.
#include <cstddef>
#include <string>
#include <string_view>

namespace crowdlab {

/// Longest value quote_value() shows, in bytes (before escapes).
inline constexpr std::size_t kMaxQuotedBytes = 80;

/// `value` with control and invalid-UTF-8 bytes as \xNN (keeping '\n' and '\t' when `keep_layout`), cut
/// after `max_bytes` input bytes (at a character boundary) with "... (N more bytes)".
std::string printable_excerpt(std::string_view value, std::size_t max_bytes, bool keep_layout = false);

/// "'<printable_excerpt(value, kMaxQuotedBytes)>'".
std::string quote_value(std::string_view value);

/// A whole message made safe: printable_excerpt with layout kept, every run of more than 400 bytes without
/// a space cut to 400 (longer than any path a test or user gives), and the whole cut to its first 3,000 and
/// last 500 bytes past 4,000 (the tail keeps hints such as the option that raises a limit).
std::string message_excerpt(std::string_view message);

}  // namespace crowdlab
