#include "framework/surface/triangle_bvh.hpp"

#include <algorithm>
#include <cmath>

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

namespace {
bool segment_box(const Vec3& p, const Vec3& d, const Eigen::AlignedBox3d& box) {
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-300) {
      if (p[k] < box.min()[k] || p[k] > box.max()[k]) return false;
      continue;
    }
    double a = (box.min()[k] - p[k]) / d[k], b = (box.max()[k] - p[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}
}  // namespace

bool TriangleBvh::segment_hits(const Vec3& p, const Vec3& q, double margin) const {
  const Vec3 d = q - p;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[static_cast<size_t>(stack[--top])];
    if (!segment_box(p, d, n.box)) continue;
    if (n.left < 0) {
      for (int i = n.first; i < n.first + n.count; ++i) {
        const int f = order_[static_cast<size_t>(i)];
        const Vec3 a = mesh_.corner(f, 0), e1 = mesh_.corner(f, 1) - a, e2 = mesh_.corner(f, 2) - a;
        const Vec3 h = d.cross(e2);
        const double det = e1.dot(h);
        if (std::abs(det) < 1e-14) continue;
        const Vec3 s = p - a;
        const double u = s.dot(h) / det;
        if (u < 0 || u > 1) continue;
        const Vec3 qv = s.cross(e1);
        const double v = d.dot(qv) / det;
        if (v < 0 || u + v > 1) continue;
        const double t = e2.dot(qv) / det;
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
