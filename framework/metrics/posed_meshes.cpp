#include "framework/metrics/posed_meshes.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/forward_kinematics.hpp"

namespace crowdlab {

std::vector<PosedMesh> posed_meshes(const CrowdAnimation& crowd, int f) {
  std::vector<PosedMesh> out;
  for (size_t c = 0; c < crowd.characters.size(); ++c) {
    const CharacterAnimation& ch = crowd.characters[c];
    if (!ch.mesh) continue;
    PosedMesh m;
    m.character = static_cast<int>(c);
    m.vertices = skin_vertices(*ch.mesh, forward_kinematics(ch.shape, ch.frames[static_cast<size_t>(f)]));
    m.normals = vertex_normals(m.vertices, ch.mesh->triangles);
    for (const Vec3& v : m.vertices) m.bounds.extend(v);
    out.push_back(std::move(m));
  }
  return out;
}

std::vector<int> mesh_sample_frames(const CrowdAnimation& crowd, int first_frame, double interval_s) {
  const int stride = std::max(1, static_cast<int>(std::lround(interval_s * crowd.meta.fps)));
  std::vector<int> frames;
  for (int f = std::max(0, first_frame); f < crowd.frame_count(); f += stride) frames.push_back(f);
  return frames;
}

}  // namespace crowdlab
