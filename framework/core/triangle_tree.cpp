#include "framework/core/triangle_tree.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "framework/core/segment_triangle.hpp"

namespace crowdlab {

Vec3 closest_point_barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Voronoi regions of the triangle's vertices, edges and face, in turn.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = va + vb + vc;
  if (!(denom > 0)) return {1, 0, 0};  // degenerate triangle: its first vertex
  const double v = vb / denom, w = vc / denom;
  return {1 - v - w, v, w};
}

TriangleTree::TriangleTree(const std::vector<Vec3>& vertices, const std::vector<Eigen::Vector3i>& triangles)
    : vertices_(vertices), triangles_(triangles) {
  const int n = static_cast<int>(triangles.size());
  order_.resize(static_cast<size_t>(n));
  centroid_.resize(static_cast<size_t>(n));
  for (int t = 0; t < n; ++t) {
    order_[static_cast<size_t>(t)] = t;
    const Eigen::Vector3i& tri = triangles[static_cast<size_t>(t)];
    centroid_[static_cast<size_t>(t)] =
        (vertices[static_cast<size_t>(tri[0])] + vertices[static_cast<size_t>(tri[1])] +
         vertices[static_cast<size_t>(tri[2])]) /
        3.0;
  }
  nodes_.reserve(static_cast<size_t>(std::max(1, n / 2)));
  if (n > 0)
    build(0, n);  // the root is the first node appended
  else
    nodes_.emplace_back();
}

Aabb TriangleTree::triangle_box(int t) const {
  Aabb box;
  for (int k = 0; k < 3; ++k)
    box.extend(vertices_[static_cast<size_t>(triangles_[static_cast<size_t>(t)][k])]);
  return box;
}

int TriangleTree::build(int first, int count) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Aabb box, centres;
  for (int i = first; i < first + count; ++i) {
    const int t = order_[static_cast<size_t>(i)];
    box.extend(triangle_box(t));
    centres.extend(centroid_[static_cast<size_t>(t)]);
  }
  nodes_[static_cast<size_t>(index)].box = box;
  constexpr int kLeafSize = 4;
  if (count <= kLeafSize) {
    nodes_[static_cast<size_t>(index)].first = first;
    nodes_[static_cast<size_t>(index)].count = count;
    return index;
  }
  int axis = 0;
  (centres.hi - centres.lo).maxCoeff(&axis);
  const auto begin = order_.begin() + first, mid = begin + count / 2, end = begin + count;
  std::nth_element(begin, mid, end, [&](int a, int b) {
    const double ca = centroid_[static_cast<size_t>(a)][axis], cb = centroid_[static_cast<size_t>(b)][axis];
    return ca < cb || (ca == cb && a < b);  // ties by index: the same tree on every run
  });
  const int left = build(first, count / 2);
  const int right = build(first + count / 2, count - count / 2);
  nodes_[static_cast<size_t>(index)].left = left;
  nodes_[static_cast<size_t>(index)].right = right;
  return index;
}

TriangleHit TriangleTree::closest(const Vec3& p) const {
  TriangleHit best;
  if (triangles_.empty()) return best;
  double best_sq = std::numeric_limits<double>::infinity();
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[static_cast<size_t>(stack[--top])];
    if (node.box.squared_distance(p) >= best_sq) continue;
    if (node.left < 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const int t = order_[static_cast<size_t>(i)];
        const Eigen::Vector3i& tri = triangles_[static_cast<size_t>(t)];
        const Vec3& a = vertices_[static_cast<size_t>(tri[0])];
        const Vec3& b = vertices_[static_cast<size_t>(tri[1])];
        const Vec3& c = vertices_[static_cast<size_t>(tri[2])];
        const Vec3 w = closest_point_barycentric(p, a, b, c);
        const Vec3 q = w[0] * a + w[1] * b + w[2] * c;
        const double d = (p - q).squaredNorm();
        if (d < best_sq) {
          best_sq = d;
          best.triangle = t;
          best.barycentric = w;
          best.point = q;
        }
      }
      continue;
    }
    // Push the farther child first so the nearer one is searched first.
    const double dl = nodes_[static_cast<size_t>(node.left)].box.squared_distance(p);
    const double dr = nodes_[static_cast<size_t>(node.right)].box.squared_distance(p);
    const bool left_first = dl <= dr;
    stack[top++] = left_first ? node.right : node.left;
    stack[top++] = left_first ? node.left : node.right;
  }
  best.distance = std::sqrt(best_sq);
  return best;
}

bool TriangleTree::ray_hits(const Vec3& origin, const Vec3& dir, double min_t, double max_t) const {
  if (triangles_.empty()) return false;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[static_cast<size_t>(stack[--top])];
    if (!segment_meets_box(origin, dir, node.box.lo, node.box.hi, min_t, max_t)) continue;
    if (node.left >= 0) {
      stack[top++] = node.left;
      stack[top++] = node.right;
      continue;
    }
    for (int i = node.first; i < node.first + node.count; ++i) {
      const Eigen::Vector3i& tri = triangles_[static_cast<size_t>(order_[static_cast<size_t>(i)])];
      const double t =
          segment_triangle_t(origin, dir, vertices_[static_cast<size_t>(tri[0])],
                             vertices_[static_cast<size_t>(tri[1])], vertices_[static_cast<size_t>(tri[2])]);
      if (t > min_t && t < max_t) return true;
    }
  }
  return false;
}

std::vector<bool> boundary_vertices(int vertex_count, const std::vector<Eigen::Vector3i>& triangles) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(3 * triangles.size());
  for (const Eigen::Vector3i& t : triangles)
    for (int k = 0; k < 3; ++k) edges.emplace_back(std::minmax(t[k], t[(k + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  std::vector<bool> rim(static_cast<size_t>(vertex_count), false);
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1)
      rim[static_cast<size_t>(edges[i].first)] = rim[static_cast<size_t>(edges[i].second)] = true;
    i = j;
  }
  return rim;
}

double TriangleTree::signed_distance(const Vec3& p, const std::vector<Vec3>& normals,
                                     const std::vector<bool>& on_rim, TriangleHit* hit_out) const {
  const TriangleHit hit = closest(p);
  if (hit_out) *hit_out = hit;
  if (hit.triangle < 0) return std::numeric_limits<double>::infinity();
  const Eigen::Vector3i& tri = triangles_[static_cast<size_t>(hit.triangle)];
  if (!on_rim.empty()) {
    bool rim = true;
    for (int k = 0; k < 3; ++k)
      if (hit.barycentric[k] > 0 && !on_rim[static_cast<size_t>(tri[k])]) rim = false;
    if (rim) return hit.distance;
  }
  const Vec3 n = hit.barycentric[0] * normals[static_cast<size_t>(tri[0])] +
                 hit.barycentric[1] * normals[static_cast<size_t>(tri[1])] +
                 hit.barycentric[2] * normals[static_cast<size_t>(tri[2])];
  return (p - hit.point).dot(n) < 0 ? -hit.distance : hit.distance;
}

}  // namespace crowdlab
