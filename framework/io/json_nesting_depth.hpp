#pragma once
// The deepest nesting of arrays and objects in a JSON text, found by one linear scan (strings and their
// escapes skipped) without building anything. JSON parsers that recurse per level (nlohmann::json, used
// by tinygltf) overflow the stack on input nested some 20,000 levels deep, so readers check this first
// (issue 21). The scan is not a validator: malformed text is left to the parser.
#include <cstddef>
#include <string_view>

namespace crowdlab {

/// Maximum depth of `[` / `{` nesting in `json` (0 for a scalar); stops counting once `stop_at` is
/// exceeded, so the result is at most stop_at + 1.
std::size_t json_nesting_depth(std::string_view json, std::size_t stop_at);

/// Byte offset of the first `[` / `{` that opens level `limit + 1`, or std::string_view::npos when the
/// text nests at most `limit` levels deep (for messages that say where, issue 32).
std::size_t json_nesting_exceeded_at(std::string_view json, std::size_t limit);

}  // namespace crowdlab
