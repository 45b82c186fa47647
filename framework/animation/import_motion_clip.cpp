#include "framework/animation/import_motion_clip.hpp"

#include "framework/animation/gltf_motion.hpp"

namespace crowdlab {

BvhMotion import_motion_clip(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  return ext == ".gltf" || ext == ".glb" ? import_gltf_animation(path) : import_bvh(path);
}

}  // namespace crowdlab
