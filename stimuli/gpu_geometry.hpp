#pragma once
// GPU geometry for the renderer (requires a current GL context): vertex/index buffers with their
// vertex-array layouts for mannequin meshes (skinned) and static geometry (ground, boxes, meshes),
// plus the ground's noise texture.
#include <cstdint>
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "stimuli/mannequin_mesh.hpp"

namespace crowdlab::stimuli {

struct GpuMesh {
  unsigned vao = 0, vbo = 0, ibo = 0;
  int count = 0;           ///< number of indices
  bool two_sided = false;  ///< MannequinMesh::two_sided
};

/// Static vertex: position and normal (world or model frame, metres).
struct StaticVertex {
  float position[3];
  float normal[3];
};

/// Attributes 0 position, 1 normal.
GpuMesh upload_static(const std::vector<StaticVertex>& vertices, const std::vector<std::uint32_t>& indices);
/// Attributes 0 position, 1 normal, 2 bones (uvec4), 3 weights (normalised), 4 region (uint),
/// 5 colour (normalised sRGB + alpha).
GpuMesh upload_mannequin(const MannequinMesh& mesh);
/// Deletes the buffers and resets `m`.
void destroy(GpuMesh& m);
/// The unit cube [-1, 1]^3 with per-face normals, counter-clockwise outside.
GpuMesh make_unit_cube();
/// A flat-shaded copy of an environment mesh (one normal per triangle).
GpuMesh make_environment_mesh(const TriangleMesh& mesh);
/// A 256 x 256 tiling value-noise texture (GL_R8, mip-mapped, repeat), from a fixed seed.
unsigned make_noise_texture();

}  // namespace crowdlab::stimuli
