#pragma once
// An AABB tree over a SurfaceMesh's triangles for exact segment queries. Used as ground truth for
// visibility (does the straight segment between two bodies pass through the surface?), which the
// cheap disk test of seed 002 approximates.
#include <vector>

#include "framework/surface/surface_mesh.hpp"

namespace crowdlab {

class TriangleBvh {
 public:
  explicit TriangleBvh(const SurfaceMesh& mesh);
  /// True when the open segment (p, q) intersects any triangle (Moller-Trumbore), ignoring hits
  /// within `end_margin` (fraction of the length) of either end.
  bool segment_hits(const Vec3& p, const Vec3& q, double end_margin = 1e-6) const;

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int left = -1, right = -1;  ///< children, or -1 for a leaf
    int first = 0, count = 0;   ///< leaf range in order_
  };
  int build(int first, int count, int depth);
  const SurfaceMesh& mesh_;
  std::vector<Node> nodes_;
  std::vector<int> order_;
  std::vector<Vec3> centroids_;
};

}  // namespace crowdlab
