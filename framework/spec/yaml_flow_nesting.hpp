#pragma once
// Where a YAML text's flow collections (`[...]`, `{...}`) start to nest deeper than a bound, found by one
// linear text scan. yaml-cpp refuses nesting past its own limit (kYamlParserDepthLimit) with the bare
// message "bad file" and, for flow collections, a position at the end of the nest or at the file's start
// (issue 21); the spec loader uses this scan to point at the nest instead. The scan is not a parser: it
// skips comments and quoted scalars, and counts a bracket in block context only where a node can start
// (after white space or at a line start), which is enough to locate a nest yaml-cpp has already refused.
#include <cstddef>
#include <string_view>

namespace crowdlab {

/// yaml-cpp 0.7's DepthGuard<500> in its document parser: lists and maps (block or flow) nested deeper
/// than this are refused by the parser itself.
inline constexpr int kYamlParserDepthLimit = 500;

/// Byte offset of the outermost opening bracket of the first flow collection that nests more than
/// `depth` levels deep, or npos when none does.
std::size_t deep_flow_nesting_start(std::string_view yaml, std::size_t depth);

}  // namespace crowdlab
