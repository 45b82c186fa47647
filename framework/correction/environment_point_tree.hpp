#pragma once
// Static environment for body-environment collisions (seed 000 §3.4): "we point-sample static
// environment objects, build a static AABB-tree, and cull collisions against body AABBs. For colliding
// points, we compute the penetration depth with respect to the collision capsule."
//
// Boxes are sampled on their six faces and triangle meshes on every triangle, on a grid of the given
// spacing (metres); the points go into a static AABB tree (median split on the longest axis, leaves of
// up to kLeafSize points), queried with an axis-aligned box. Points are in world coordinates (metres).
// A capsule wholly inside a closed obstacle touches no surface point and is not pushed out: the
// correction starts from animations that are, at worst, shallowly inside the environment.
#include <cstdint>
#include <string>
#include <vector>

#include "framework/core/capsule_box.hpp"
#include "framework/core/crowd_animation.hpp"
#include "framework/core/math_types.hpp"

namespace crowdlab {

/// Memory per sample point: the point (24 B) and its share of the tree (2 nodes of 64 B per 8 points).
inline constexpr double kEnvironmentBytesPerPoint = 40.0;

/// Upper bound on the points sampling `env` at `spacing_m` makes (the sampling grid of every box face
/// and every triangle's parallelogram), computed without sampling. Throws InputError "<context>: ..."
/// with the estimate, its memory and the largest contributor when it passes `max_points`, or when the
/// spacing is not > 0.
void check_environment_sampling(const Environment& env, double spacing_m, double max_points,
                                const std::string& context);

class EnvironmentPointTree {
 public:
  static constexpr int kLeafSize = 8;

  EnvironmentPointTree() = default;
  /// Samples env.boxes and env.meshes (the ground plane is handled analytically elsewhere).
  /// Throws InputError for non-finite geometry, a spacing <= 0, or more than `max_points` points
  /// (check_environment_sampling).
  EnvironmentPointTree(const Environment& env, double spacing_m, double max_points);

  bool empty() const { return points_.empty(); }
  const std::vector<Vec3>& points() const { return points_; }
  /// Bounds of all points (an empty box when there are none).
  Aabb bounds() const { return nodes_.empty() ? Aabb{} : nodes_.front().box; }

  /// Calls visit(point_index) for every point inside `box`, in a fixed (tree) order. No allocation.
  template <class Visit>
  void query(const Aabb& box, Visit&& visit) const {
    if (nodes_.empty()) return;
    int stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[static_cast<size_t>(stack[--top])];
      if (!n.box.overlaps(box)) continue;
      if (n.left < 0) {
        for (int i = n.begin; i < n.end; ++i)
          if (box.contains(points_[static_cast<size_t>(i)])) visit(i);
      } else {
        stack[top++] = n.right;
        stack[top++] = n.left;
      }
    }
  }

 private:
  struct Node {
    Aabb box;
    int left = -1, right = -1;  ///< children (-1 for a leaf)
    int begin = 0, end = 0;     ///< point range of a leaf
  };
  int build(int begin, int end, int depth);
  std::vector<Vec3> points_;
  std::vector<Node> nodes_;
};

}  // namespace crowdlab
