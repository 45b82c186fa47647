#include "framework/io/untrusted_json.hpp"

#include "framework/core/error.hpp"
#include "framework/core/file_kind.hpp"
#include "framework/io/json_nesting_depth.hpp"

namespace crowdlab {
namespace {

SourceLocation where(const std::string& file, int line) {
  return SourceLocation{file, line, 0, ""};
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
    throw InputError(where(file, line), "JSON nests arrays/objects more than " +
                                            std::to_string(limits.max_depth) + " levels deep at byte " +
                                            std::to_string(offset + deep) +
                                            " (the limit; crowdlab's own files need fewer than 10 levels)");
}

nlohmann::json parse_untrusted_json(std::string_view text, const std::string& file, const JsonLimits& limits,
                                    std::size_t offset, int line) {
  check_untrusted_json(text, file, limits, offset, line);
  try {
    return nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte counts from 1 at the character after the error's last read one.
    const std::size_t at = offset + (e.byte > 0 ? e.byte - 1 : 0);
    std::string why = e.what();
    const std::size_t colon = why.find(": ", why.find("parse error"));
    if (colon != std::string::npos) why = why.substr(colon + 2);
    constexpr std::size_t kMaxReason = 200;  // the parser quotes the offending token whole
    if (why.size() > kMaxReason) why = why.substr(0, kMaxReason) + "...";
    throw InputError(where(file, line), "not valid JSON at byte " + std::to_string(at) + ": " + why);
  }
}

nlohmann::json read_untrusted_json(const std::filesystem::path& path, const std::string& what,
                                   const JsonLimits& limits) {
  const std::string text = read_regular_file(path, what, limits.max_bytes, limits.raise_with);
  return parse_untrusted_json(text, path.string(), limits);
}

}  // namespace crowdlab
