#pragma once
// The rendered surfaces of a crowd on a frame: every character's skinned mesh (CharacterAnimation::mesh:
// the MPFB2 skin with the garments, hair, eyes and shoes fitted to it, as the renderer draws it at full
// detail) posed by linear blend skinning (core/skinned_mesh.hpp), with vertex normals and bounds; and
// the frames the mesh-level measures (mesh_overlap.hpp, proxy_coverage.hpp) sample.
#include <vector>

#include "framework/core/aabb.hpp"
#include "framework/core/crowd_animation.hpp"

namespace crowdlab {

struct PosedMesh {
  int character = -1;          ///< index in the crowd
  std::vector<Vec3> vertices;  ///< world, metres
  std::vector<Vec3> normals;   ///< unit, area-weighted
  Aabb bounds;
};

/// The posed meshes of the characters that carry one, on frame f (characters without a mesh, e.g.
/// procedural bodies, are left out).
std::vector<PosedMesh> posed_meshes(const CrowdAnimation& crowd, int f);

/// Frames from first_frame on, one every interval_s seconds (at least every frame): the mesh measures
/// cost about a million point queries per frame at 60 characters, so they sample the clip.
std::vector<int> mesh_sample_frames(const CrowdAnimation& crowd, int first_frame, double interval_s);

}  // namespace crowdlab
