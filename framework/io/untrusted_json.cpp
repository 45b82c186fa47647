#include "framework/io/untrusted_json.hpp"

#include <algorithm>

#include "framework/core/error.hpp"
#include "framework/core/file_kind.hpp"
#include "framework/io/json_nesting_depth.hpp"

namespace crowdlab {
namespace {

SourceLocation where(const std::string& file, int line) {
  return SourceLocation{file, line, 0, ""};
}

/// The line of byte `at` of a whole text file (`offset` 0), for messages; 0 (none) for a text inside a
/// binary container or a CSV cell, whose caller gives the line.
int line_of(std::string_view text, std::size_t at, std::size_t offset, int line) {
  if (line > 0 || offset > 0) return line;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

std::string raise_hint(const JsonLimits& limits) {
  return limits.raise_with.empty() ? "" : "; raise it with " + limits.raise_with;
}

}  // namespace

void check_untrusted_json(std::string_view text, const std::string& file, const JsonLimits& limits,
                          std::size_t offset, int line) {
  if (text.size() > limits.max_bytes)
    throw InputError(where(file, line), "JSON of " + std::to_string(text.size()) + " bytes at byte " +
                                            std::to_string(offset) + " is larger than the limit of " +
                                            std::to_string(limits.max_bytes) + " bytes" + raise_hint(limits));
  const std::size_t deep = json_nesting_exceeded_at(text, limits.max_depth);
  if (deep != std::string_view::npos)
    throw InputError(where(file, line_of(text, deep, offset, line)),
                     "JSON nests arrays/objects more than " + std::to_string(limits.max_depth) +
                         " levels deep at byte " + std::to_string(offset + deep) +
                         " (the limit; crowdlab's own files need fewer than 10 levels)");
}

nlohmann::json parse_untrusted_json(std::string_view text, const std::string& file, const JsonLimits& limits,
                                    std::size_t offset, int line) {
  check_untrusted_json(text, file, limits, offset, line);
  try {
    return nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte counts from 1 at the character after the error's last read one.
    const std::size_t in_text = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    const std::size_t at = offset + in_text;
    std::string why = e.what();
    const std::size_t colon = why.find(": ", why.find("parse error"));
    if (colon != std::string::npos) why = why.substr(colon + 2);
    constexpr std::size_t kMaxReason = 200;  // the parser quotes the offending token whole
    if (why.size() > kMaxReason) why = why.substr(0, kMaxReason) + "...";
    throw InputError(where(file, line_of(text, in_text, offset, line)),
                     "not valid JSON at byte " + std::to_string(at) + ": " + why);
  }
}

nlohmann::json read_untrusted_json(const std::filesystem::path& path, const std::string& what,
                                   const JsonLimits& limits) {
  const std::string text = read_regular_file(path, what, limits.max_bytes, limits.raise_with);
  return parse_untrusted_json(text, path.string(), limits);
}

}  // namespace crowdlab
