#include "framework/surface/triangle_bvh.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/segment_triangle.hpp"

namespace crowdlab {

TriangleBvh::TriangleBvh(const SurfaceMesh& mesh) : mesh_(mesh) {
  const int F = mesh.face_count();
  order_.resize(static_cast<size_t>(F));
  centroids_.resize(static_cast<size_t>(F));
  for (int f = 0; f < F; ++f) {
    order_[static_cast<size_t>(f)] = f;
    centroids_[static_cast<size_t>(f)] = mesh.centroid(f);
  }
  nodes_.reserve(static_cast<size_t>(2 * F));
  build(0, F, 0);
}

int TriangleBvh::build(int first, int count, int depth) {
  Node node;
  for (int i = first; i < first + count; ++i)
    for (int k = 0; k < 3; ++k) node.box.extend(mesh_.corner(order_[static_cast<size_t>(i)], k));
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back(node);
  if (count <= 4 || depth > 40) {
    nodes_[static_cast<size_t>(index)].first = first;
    nodes_[static_cast<size_t>(index)].count = count;
    return index;
  }
  int axis = 0;
  node.box.sizes().maxCoeff(&axis);
  const int mid = first + count / 2;
  std::nth_element(
      order_.begin() + first, order_.begin() + mid, order_.begin() + first + count, [&](int a, int b) {
        return centroids_[static_cast<size_t>(a)][axis] < centroids_[static_cast<size_t>(b)][axis] ||
               (centroids_[static_cast<size_t>(a)][axis] == centroids_[static_cast<size_t>(b)][axis] &&
                a < b);
      });
  const int l = build(first, mid - first, depth + 1);
  const int r = build(mid, first + count - mid, depth + 1);
  nodes_[static_cast<size_t>(index)].left = l;
  nodes_[static_cast<size_t>(index)].right = r;
  return index;
}

bool TriangleBvh::segment_hits(const Vec3& p, const Vec3& q, double margin) const {
  const Vec3 d = q - p;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[static_cast<size_t>(stack[--top])];
    if (!segment_meets_box(p, d, n.box.min(), n.box.max(), 0.0, 1.0)) continue;
    if (n.left < 0) {
      for (int i = n.first; i < n.first + n.count; ++i) {
        const int f = order_[static_cast<size_t>(i)];
        const double t = segment_triangle_t(p, d, mesh_.corner(f, 0), mesh_.corner(f, 1), mesh_.corner(f, 2));
        if (t > margin && t < 1 - margin) return true;
      }
    } else if (top + 2 <= 128) {
      stack[top++] = n.left;
      stack[top++] = n.right;
    }
  }
  return false;
}

}  // namespace crowdlab
