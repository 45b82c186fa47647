#pragma once
// Parses a glTF 2.0 file into a tinygltf::Model: binary (.glb) by extension, otherwise JSON (.gltf with
// its external buffers). Shared by every reader of glTF input (crowd files, surface meshes, motion clips,
// skinned characters), which then read accessors through gltf_accessor_reader.hpp.
#include <tiny_gltf.h>

#include <filesystem>

namespace crowdlab {

/// Deepest JSON nesting of arrays/objects accepted (glTF itself needs fewer than 10 levels; deeper
/// `extras` are refused before parsing, since the parser recurses per level and would overflow the stack).
inline constexpr std::size_t kMaxGltfJsonDepth = 256;

/// Throws InputError "<path>: no such file" for a missing file and
/// "<path>: cannot read glTF: <parser message>" for a file tinygltf cannot parse (truncated JSON, a
/// missing .bin, a bad header), and for JSON nested deeper than kMaxGltfJsonDepth.
tinygltf::Model load_gltf_model(const std::filesystem::path& path);

}  // namespace crowdlab
