#pragma once
// Which points lie inside another character's rendered surface on one frame (issue 27): the inside
// test that the mesh-level overlap (mesh_overlap.hpp) counts and that overlap mode (stimuli/renderer.hpp)
// paints, kept in one place so that what is measured is what is shown.
//
// Input: a crowd and a frame. The rendered surfaces are the posed meshes of the characters that carry
// one (posed_meshes.hpp). For a point p and the character `self` it belongs to,
//   depth(p) = max over b != self with p inside b's bounding box of -s_b(p), counting only
//              0 < -s_b(p) <= max_depth_m (deeper reads are a failed sign test: mesh_overlap.hpp),
// with s_b the signed distance to b's mesh (core/triangle_tree.hpp: closest point, sign from the
// interpolated vertex normals, a closest point on an open sheet's rim counting as outside), and an
// inside sign counting only when the ray from p away from its closest point meets b's surface again
// (from inside a closed surface every ray does). 0: outside every other character. Metres.
// Why the ray (issue 27, session 25): where the closest point lies on a fold of a thin shell (a shoe's
// collar, where its outer face turns into its lining) the interpolated normal can point away from a
// point far outside. On the 5 s D5 concert, 91 % of the vertices counted inside with fitted proxies were
// 5-20 cm "deep", a foot's skin in its own shoe 15 cm beside a neighbour's shoe among them; the ray from
// such a point meets nothing of the neighbour.
// Every tree a query can need is built in the constructor, so const queries may run in parallel.
#include <memory>
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "framework/core/triangle_tree.hpp"
#include "framework/metrics/posed_meshes.hpp"

namespace crowdlab {

class FrameSurfaces {
 public:
  FrameSurfaces(const CrowdAnimation& crowd, int frame);
  FrameSurfaces(const FrameSurfaces&) = delete;  // the trees refer to meshes_'s vectors
  FrameSurfaces& operator=(const FrameSurfaces&) = delete;

  /// The posed meshes of the frame (characters without a mesh left out).
  const std::vector<PosedMesh>& meshes() const { return meshes_; }

  /// depth(p) of the header for a point of character `self` (a crowd index; -1: of no character);
  /// *by (when given) is the character it is deepest inside, -1 when outside all.
  double inside_depth(const Vec3& p, int self, double max_depth_m, int* by = nullptr) const;

 private:
  const CrowdAnimation& crowd_;
  std::vector<PosedMesh> meshes_;
  std::vector<std::unique_ptr<TriangleTree>>
      trees_;                            ///< per mesh; null when no other mesh's box meets its box
  std::vector<std::vector<bool>> rims_;  ///< per mesh with a tree: boundary_vertices()
};

}  // namespace crowdlab
