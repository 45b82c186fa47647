#pragma once
// Parses a glTF 2.0 file into a tinygltf::Model: binary (.glb) by extension, otherwise JSON (.gltf with
// its external buffers). Shared by every reader of glTF input (crowd files, surface meshes, motion clips,
// skinned characters), which then read accessors through gltf_accessor_reader.hpp.
#include <tiny_gltf.h>

#include <filesystem>

namespace crowdlab {

/// Throws InputError "<path>: no such file" for a missing file and
/// "<path>: cannot read glTF: <parser message>" for a file tinygltf cannot parse (truncated JSON, a
/// missing .bin, a bad header).
tinygltf::Model load_gltf_model(const std::filesystem::path& path);

}  // namespace crowdlab
