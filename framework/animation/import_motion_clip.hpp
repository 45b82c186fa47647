#pragma once
// One motion clip file, read as `run` reads it: a .gltf/.glb animation (gltf_motion.hpp) or else a BVH
// file (bvh.hpp). `validate` calls the same function, so that it refuses the clips `run` would refuse
// (issue 33 item 2).
#include <filesystem>

#include "framework/animation/bvh.hpp"

namespace crowdlab {

/// Reads `path` by its extension; throws InputError naming the file and its place for a bad clip.
BvhMotion import_motion_clip(const std::filesystem::path& path);

}  // namespace crowdlab
