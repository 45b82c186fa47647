#include "framework/metrics/surfaces_inside.hpp"

namespace crowdlab {

FrameSurfaces::FrameSurfaces(const CrowdAnimation& crowd, int frame)
    : crowd_(crowd), meshes_(posed_meshes(crowd, frame)) {
  trees_.resize(meshes_.size());
  rims_.resize(meshes_.size());
  for (size_t b = 0; b < meshes_.size(); ++b) {
    // A mesh no other mesh's box meets can contain no other character's point: no tree needed.
    bool met = false;
    for (size_t a = 0; a < meshes_.size() && !met; ++a)
      met = a != b && meshes_[a].bounds.overlaps(meshes_[b].bounds);
    if (!met) continue;
    const auto& tris = crowd_.characters[static_cast<size_t>(meshes_[b].character)].mesh->triangles;
    trees_[b] = std::make_unique<TriangleTree>(meshes_[b].vertices, tris);
    rims_[b] = boundary_vertices(static_cast<int>(meshes_[b].vertices.size()), tris);
  }
}

double FrameSurfaces::inside_depth(const Vec3& p, int self, double max_depth_m, int* by) const {
  double depth = 0.0;
  int deepest = -1;
  for (size_t b = 0; b < meshes_.size(); ++b) {
    if (meshes_[b].character == self || !trees_[b] || !meshes_[b].bounds.contains(p)) continue;
    const double s = trees_[b]->signed_distance(p, meshes_[b].normals, rims_[b]);
    if (s < 0.0 && -s <= max_depth_m && -s > depth) {
      depth = -s;
      deepest = meshes_[b].character;
    }
  }
  if (by) *by = deepest;
  return depth;
}

}  // namespace crowdlab
