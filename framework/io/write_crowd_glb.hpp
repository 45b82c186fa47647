#pragma once
// Writing a CrowdAnimation as a glTF 2.0 binary file (.glb). The layout is described in
// framework/io/crowd_glb_format.hpp; read it back with read_crowd_glb().
#include <string>

#include "framework/core/crowd_animation.hpp"

namespace crowdlab {

/// Writes `crowd` to `path` (.glb). The crowd is validated first (validate_crowd plus the environment:
/// finite boxes with positive extents, meshes with in-range indices), throwing InputError naming the
/// character/frame/joint or obstacle. Joint rotations and root positions are stored as 32-bit floats
/// (glTF accessors), so they read back to ~1e-7 relative; everything in extras is exact.
/// The file appears under `path` only once complete (write_file_atomic: a temporary beside it, renamed).
/// Throws RuntimeError when the file cannot be written.
void write_crowd_glb(const CrowdAnimation& crowd, const std::string& path);

}  // namespace crowdlab
