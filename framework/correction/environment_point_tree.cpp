#include "framework/correction/environment_point_tree.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "framework/core/error.hpp"

namespace crowdlab {
namespace {

// Samples the parallelogram origin + u*e1 + v*e2 (u, v in [0,1]); triangles keep u + v <= 1.
void sample_patch(const Vec3& origin, const Vec3& e1, const Vec3& e2, double spacing, bool triangle,
                  std::vector<Vec3>& out) {
  const int n1 = std::max(1, static_cast<int>(std::ceil(e1.norm() / spacing)));
  const int n2 = std::max(1, static_cast<int>(std::ceil(e2.norm() / spacing)));
  for (int i = 0; i <= n1; ++i)
    for (int k = 0; k <= n2; ++k) {
      const double u = static_cast<double>(i) / n1, v = static_cast<double>(k) / n2;
      if (triangle && u + v > 1.0 + 1e-12) continue;
      out.push_back(origin + u * e1 + v * e2);
    }
}

// Grid points sample_patch visits for edges of these lengths (in double: a fuzzed 1e300 m box overflows
// int). Non-finite geometry counts 0: the sampler refuses it with its own message.
double patch_grid_points(double e1_m, double e2_m, double spacing) {
  if (!std::isfinite(e1_m) || !std::isfinite(e2_m)) return 0.0;
  return (std::max(1.0, std::ceil(e1_m / spacing)) + 1) * (std::max(1.0, std::ceil(e2_m / spacing)) + 1);
}

// A count or a size for messages: whole numbers below ten million in full, others to 4 digits.
std::string number(double v) {
  char s[32];
  std::snprintf(s, sizeof s, v == std::floor(v) && std::abs(v) < 1e7 ? "%.0f" : "%.4g", v);
  return s;
}

}  // namespace

void check_environment_sampling(const Environment& env, double spacing_m, double max_points,
                                const std::string& context) {
  if (!(spacing_m > 0.0) || !std::isfinite(spacing_m))
    throw InputError(context + ": environment sample spacing must be > 0, got " + std::to_string(spacing_m));
  double total = 0.0, largest = -1.0;
  std::string largest_name;
  for (size_t b = 0; b < env.boxes.size(); ++b) {
    const Vec3 size = 2.0 * env.boxes[b].half_extents_m;
    double points = 0.0;
    for (int axis = 0; axis < 3; ++axis)
      points += 2.0 * patch_grid_points(size[(axis + 1) % 3], size[(axis + 2) % 3], spacing_m);
    total += points;
    if (points > largest) {
      largest = points;
      largest_name = "box " + std::to_string(b) + " (" + number(size.x()) + " x " + number(size.y()) + " x " +
                     number(size.z()) + " m)";
    }
  }
  for (const TriangleMesh& mesh : env.meshes) {
    double points = 0.0;
    for (const Eigen::Vector3i& t : mesh.triangles) {
      if ((t.array() < 0).any() || (t.array() >= static_cast<int>(mesh.vertices_m.size())).any()) continue;
      const Vec3& a = mesh.vertices_m[static_cast<size_t>(t[0])];
      points += patch_grid_points((mesh.vertices_m[static_cast<size_t>(t[1])] - a).norm(),
                                  (mesh.vertices_m[static_cast<size_t>(t[2])] - a).norm(), spacing_m);
    }
    total += points;
    if (points > largest) {
      largest = points;
      largest_name = "mesh '" + mesh.name + "'";
    }
  }
  if (total > max_points)
    throw InputError(context + ": sampling the environment every " + number(spacing_m * 100.0) +
                     " cm would make up to " + number(total) + " points (about " +
                     number(total * kEnvironmentBytesPerPoint / 1e9) + " GB), more than the limit of " +
                     number(max_points) + " (--max-environment-points); the largest part is " + largest_name);
}

EnvironmentPointTree::EnvironmentPointTree(const Environment& env, double spacing_m, double max_points) {
  check_environment_sampling(env, spacing_m, max_points, "environment");
  for (size_t b = 0; b < env.boxes.size(); ++b) {
    const Box& box = env.boxes[b];
    if (!box.center_m.allFinite() || !box.half_extents_m.allFinite() || !box.rotation.coeffs().allFinite() ||
        (box.half_extents_m.array() < 0.0).any())
      throw InputError("environment box " + std::to_string(b) + " has non-finite or negative geometry");
    const Mat3 r = box.rotation.normalized().toRotationMatrix();
    for (int axis = 0; axis < 3; ++axis)
      for (int side : {-1, 1}) {
        const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
        const Vec3 normal_offset = r.col(axis) * (side * box.half_extents_m[axis]);
        const Vec3 e1 = r.col(a1) * (2.0 * box.half_extents_m[a1]);
        const Vec3 e2 = r.col(a2) * (2.0 * box.half_extents_m[a2]);
        sample_patch(box.center_m + normal_offset - 0.5 * e1 - 0.5 * e2, e1, e2, spacing_m, false, points_);
      }
  }
  for (const TriangleMesh& mesh : env.meshes) {
    for (const Eigen::Vector3i& t : mesh.triangles) {
      for (int c = 0; c < 3; ++c)
        if (t[c] < 0 || static_cast<size_t>(t[c]) >= mesh.vertices_m.size())
          throw InputError("environment mesh '" + mesh.name + "' has a triangle index out of range");
      const Vec3& a = mesh.vertices_m[static_cast<size_t>(t[0])];
      const Vec3& b = mesh.vertices_m[static_cast<size_t>(t[1])];
      const Vec3& c = mesh.vertices_m[static_cast<size_t>(t[2])];
      if (!a.allFinite() || !b.allFinite() || !c.allFinite())
        throw InputError("environment mesh '" + mesh.name + "' has a non-finite vertex");
      sample_patch(a, b - a, c - a, spacing_m, true, points_);
    }
  }
  if (!points_.empty()) {
    nodes_.reserve(2 * points_.size() / kLeafSize + 2);
    build(0, static_cast<int>(points_.size()), 0);
  }
}

int EnvironmentPointTree::build(int begin, int end, int depth) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Aabb box;
  for (int i = begin; i < end; ++i) box.extend(points_[static_cast<size_t>(i)]);
  nodes_[static_cast<size_t>(index)].box = box;
  if (end - begin <= kLeafSize || depth >= 60) {
    nodes_[static_cast<size_t>(index)].begin = begin;
    nodes_[static_cast<size_t>(index)].end = end;
    return index;
  }
  int axis = 0;
  (box.hi - box.lo).maxCoeff(&axis);
  const int mid = (begin + end) / 2;
  std::nth_element(points_.begin() + begin, points_.begin() + mid, points_.begin() + end,
                   [axis](const Vec3& p, const Vec3& q) { return p[axis] < q[axis]; });
  const int left = build(begin, mid, depth + 1);
  const int right = build(mid, end, depth + 1);
  nodes_[static_cast<size_t>(index)].left = left;
  nodes_[static_cast<size_t>(index)].right = right;
  return index;
}

}  // namespace crowdlab
