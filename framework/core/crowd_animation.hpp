#pragma once
// The plain data that flows between pipeline stages:
//   CharacterAnimation  one body shape + its poses at a fixed fps
//   Environment         ground plane, static boxes and triangle meshes
//   CrowdAnimation      characters + environment + metadata
// No behaviour lives here beyond validation; stages are free functions over these types.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "framework/core/body_shape.hpp"
#include "framework/core/pose.hpp"
#include "framework/core/skinned_mesh.hpp"

namespace crowdlab {

struct CharacterAnimation {
  std::string name;  ///< unique within a crowd, e.g. "c007"
  BodyShape shape;
  std::vector<Pose> frames;  ///< frame f is at time f / fps seconds
  int palette = 0;           ///< appearance index for rendering (clothing/skin palette)
  /// Optional skinned body surface in the rest pose of `shape` (e.g. the shaped MPFB2 mesh). nullptr:
  /// the procedural body (renderers build a surface around the capsules). Shared and immutable, so
  /// copying a crowd does not copy meshes; the capsules in `shape` stay what correction and metrics use.
  std::shared_ptr<const SkinnedMesh> mesh;
};

/// A static oriented box (e.g. a corridor wall or a stage).
struct Box {
  Vec3 center_m = Vec3::Zero();
  Vec3 half_extents_m = Vec3::Constant(0.5);
  Quat rotation = Quat::Identity();  ///< box frame -> world
};

/// A static triangle mesh in world coordinates (metres).
struct TriangleMesh {
  std::string name;
  std::vector<Vec3> vertices_m;
  std::vector<Eigen::Vector3i> triangles;  ///< counter-clockwise seen from outside
};

struct Environment {
  bool ground_plane = true;  ///< the plane y = 0
  std::vector<Box> boxes;
  std::vector<TriangleMesh> meshes;
};

struct CrowdMetadata {
  double fps = 30.0;
  std::uint64_t seed = 0;
  std::string condition_id;
  std::string scenario;
};

struct CrowdAnimation {
  std::vector<CharacterAnimation> characters;
  Environment environment;
  CrowdMetadata meta;

  /// Number of frames (the same for every character; see validate_crowd()).
  int frame_count() const {
    return characters.empty() ? 0 : static_cast<int>(characters.front().frames.size());
  }
  double duration_s() const { return meta.fps > 0 ? frame_count() / meta.fps : 0.0; }
};

/// Checks everything a downstream stage relies on: fps > 0, at least one character, equal frame
/// counts, valid shapes and finite unit poses. Throws InputError naming character, frame and joint.
void validate_crowd(const CrowdAnimation& crowd, const std::string& context);

}  // namespace crowdlab
