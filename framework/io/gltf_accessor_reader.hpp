#pragma once
// Bounds-checked reading of glTF accessors, shared by every glTF reader (crowd files, surface meshes,
// motion clips, skinned characters).
// tinygltf parses the container but does not check that an accessor's data lies inside its buffer, so every
// read goes through here.
#include <tiny_gltf.h>

#include <cstdint>
#include <string>
#include <vector>

namespace crowdlab {

/// The floats of accessor `index`, count x components, row-major. Checks the index, component type
/// FLOAT, the element type (`type`, TINYGLTF_TYPE_*), no sparse storage, bufferView/buffer ranges and
/// that every value is finite. `context` names the file; errors read
/// "<context>: accessor <i> ('<name>'): <problem>".
std::vector<float> read_float_accessor(const tinygltf::Model& model, int index, int type,
                                       const std::string& context);

/// Unsigned integer indices (UNSIGNED_BYTE/SHORT/INT, SCALAR), with the same checks.
std::vector<std::uint32_t> read_index_accessor(const tinygltf::Model& model, int index,
                                               const std::string& context);

/// Unsigned integers (UNSIGNED_BYTE/SHORT/INT) of element type `type` (e.g. VEC4 for JOINTS_0),
/// count x components, row-major, with the same checks.
std::vector<std::uint32_t> read_uint_accessor(const tinygltf::Model& model, int index, int type,
                                              const std::string& context);

}  // namespace crowdlab
