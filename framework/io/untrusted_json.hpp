#pragma once
// The one reader of JSON that crowdlab did not write itself or that a participant's browser produced:
// web study results, session metadata (P.json), provenance sidecars, the JSON chunk of glTF files
// (issue 32). A result file whose value nested 300,000 arrays deep overflowed the stack in the parse
// (SIGSEGV), and 100,000 levels ran out of memory. The reader checks before parsing:
//   size   the text is at most `max_bytes` (a file's size is checked from stat(2) before it is read);
//   depth  arrays/objects nest at most `max_depth` levels (one linear scan, json_nesting_depth.hpp);
// and turns nlohmann::json's parse errors into InputErrors. Every refusal names the file, the byte
// offset in the file, the limit and how to raise it (JsonLimits::raise_with), and is exit 2.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace crowdlab {

struct JsonLimits {
  std::size_t max_depth = 64;             ///< crowdlab's own JSON nests fewer than 10 levels
  std::uintmax_t max_bytes = 256u << 20;  ///< 256 MiB
  std::string raise_with;                 ///< the option or key that raises max_bytes ("" when none)
};

/// Parses `text`, found at byte `offset` of `file` (0 for a whole file; the start of a GLB's JSON chunk,
/// or of a CSV cell, otherwise). `line` > 0 is added to messages (JSON lines, CSV rows).
nlohmann::json parse_untrusted_json(std::string_view text, const std::string& file, const JsonLimits& limits,
                                    std::size_t offset = 0, int line = 0);

/// Checks size and depth only (for JSON that another parser reads: tinygltf); throws like the parser.
void check_untrusted_json(std::string_view text, const std::string& file, const JsonLimits& limits,
                          std::size_t offset = 0, int line = 0);

/// Reads and parses a whole file; a FIFO, device or folder is refused before it is opened and its size is
/// checked before it is read. `what` names the file's role in messages ("web results").
nlohmann::json read_untrusted_json(const std::filesystem::path& path, const std::string& what,
                                   const JsonLimits& limits);

}  // namespace crowdlab
