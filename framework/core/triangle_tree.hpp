#pragma once
// A bounding-volume hierarchy over a triangle mesh for closest-point and signed-distance queries
// (used by the mesh-level measures of issue 27: metrics/mesh_overlap.hpp, metrics/proxy_coverage.hpp).
//
// Build: axis-aligned boxes, split at the median triangle centroid along the box's longest axis,
// leaves of at most 4 triangles (O(T log T)). Query: depth-first, nearer child first, a subtree skipped
// when its box is farther than the best distance so far (exact: the answer is the true closest point).
//
// Signed distance to a surface that is closed only as a whole (a skinned body with its garments, whose
// skin has holes where a garment covers it): s(p) = |p - c| sign((p - c) . n(c)), with c the closest
// point and n(c) the vertex normals interpolated by c's barycentric coordinates (the pseudo-normal of
// the closest feature, smoothed across faces so that the sign is continuous over edges and vertices).
// Negative inside. Units: those of the vertices (metres here). Where the closest point lies on the rim
// of an open sheet (a hair strand's tip, a sleeve's hem: only vertices on a boundary edge carry it),
// the normal says nothing about the far side, and the point counts as outside (`on_rim` flags).
//
// Ray query (ray_hits): whether a ray meets any triangle, either face (segment_triangle.hpp: the slab
// method for the boxes, Moller-Trumbore for the triangles). Used to confirm an inside sign: from a point
// inside a closed surface, every ray meets the surface (surfaces_inside.hpp says where the sign fails).
#include <vector>

#include "framework/core/aabb.hpp"
#include "framework/core/math_types.hpp"

namespace crowdlab {

/// Closest point on triangle (a, b, c) to p, as barycentric weights (u, v, w) of (a, b, c), each >= 0,
/// summing to 1.
Vec3 closest_point_barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

struct TriangleHit {
  int triangle = -1;                ///< index into the mesh's triangles (-1: empty mesh)
  Vec3 barycentric = Vec3::Zero();  ///< of the closest point
  Vec3 point = Vec3::Zero();        ///< the closest point
  double distance = 0.0;            ///< |p - point|
};

/// Per vertex: whether it lies on an edge that only one triangle uses (the rim of an open surface).
std::vector<bool> boundary_vertices(int vertex_count, const std::vector<Eigen::Vector3i>& triangles);

class TriangleTree {
 public:
  /// Keeps references to vertices and triangles: they must outlive the tree and stay unchanged.
  TriangleTree(const std::vector<Vec3>& vertices, const std::vector<Eigen::Vector3i>& triangles);

  /// The closest point of the mesh to p (triangle -1 when the mesh has no triangles).
  TriangleHit closest(const Vec3& p) const;
  /// Signed distance to the mesh (see the header) with per-vertex normals `normals` (same indexing as
  /// the vertices); +infinity for an empty mesh.
  /// With `on_rim` (per vertex, from boundary_vertices(); may be empty), a closest point whose nonzero
  /// barycentric weights all fall on rim vertices gives +distance.
  /// `hit` (optional) receives the closest point it was measured from.
  double signed_distance(const Vec3& p, const std::vector<Vec3>& normals,
                         const std::vector<bool>& on_rim = {}, TriangleHit* hit = nullptr) const;
  /// Whether the ray origin + t dir (dir unit) meets a triangle at some t in (min_t, max_t).
  bool ray_hits(const Vec3& origin, const Vec3& dir, double min_t, double max_t) const;
  /// Bounds of every vertex a triangle uses.
  const Aabb& bounds() const { return nodes_.front().box; }

 private:
  struct Node {
    Aabb box;
    int left = -1;  ///< child node indices (-1: a leaf)
    int right = -1;
    int first = 0;  ///< leaf: range [first, first + count) of order_
    int count = 0;
  };
  int build(int first, int count);
  Aabb triangle_box(int t) const;

  const std::vector<Vec3>& vertices_;
  const std::vector<Eigen::Vector3i>& triangles_;
  std::vector<int> order_;      ///< triangle indices, grouped by leaf
  std::vector<Vec3> centroid_;  ///< per triangle
  std::vector<Node> nodes_;     ///< node 0 is the root
};

}  // namespace crowdlab
