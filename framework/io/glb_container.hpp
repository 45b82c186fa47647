#pragma once
// The binary glTF container (glTF 2.0 §4.4, "GLB File Format Specification"): a 12-byte header (magic
// "glTF", version 2, total length) and then chunks of (length, type, data), the first of type JSON, an
// optional second of type BIN. tinygltf refuses a broken container with one of a few bare sentences
// ("Invalid glTF binary.") and no position; this check runs first and says what is wrong and where,
// in bytes from the start of the file (issue 21: a mutated GLB reported "cannot read glTF: unknown
// error"). Inputs: the file's bytes. Outputs: the JSON chunk's text. Nothing is allocated.
#include <string>
#include <string_view>

namespace crowdlab {

/// Offset of the JSON chunk's data from the start of a GLB file (12-byte header + 8-byte chunk header).
inline constexpr std::size_t kGlbJsonOffset = 20;

/// The JSON chunk of a GLB file's bytes, after checking the header and the chunk layout. Throws
/// InputError "<file>: cannot read glTF: not a valid GLB file: <what, with byte offsets>" for a short file, a
/// wrong magic or version, a total length past the end of the file, a chunk that runs past the total length,
/// a first chunk that is not JSON or is empty, and a second chunk that is not BIN or not 4-byte padded.
std::string_view glb_json_chunk(std::string_view bytes, const std::string& file);

}  // namespace crowdlab
