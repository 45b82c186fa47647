#include "framework/metrics/surfaces_inside.hpp"

#include <limits>

namespace crowdlab {

namespace {

/// The inside sign's confirmation (header): the ray from p away from its closest point c meets the
/// surface again. A point too close to c to give a direction (1 micrometre) is not judged here.
bool sees_surface_beyond(const TriangleTree& tree, const Vec3& p, const Vec3& c) {
  const Vec3 away = p - c;
  const double length = away.norm();
  if (length < 1e-6) return true;
  return tree.ray_hits(p, away / length, 0.0, std::numeric_limits<double>::infinity());
}

}  // namespace

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
    TriangleHit hit;
    const double s = trees_[b]->signed_distance(p, meshes_[b].normals, rims_[b], &hit);
    if (s < 0.0 && -s <= max_depth_m && -s > depth && sees_surface_beyond(*trees_[b], p, hit.point)) {
      depth = -s;
      deepest = meshes_[b].character;
    }
  }
  if (by) *by = deepest;
  return depth;
}

}  // namespace crowdlab
