#include "framework/core/crowd_penetration_depth.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

#include "framework/core/capsule_box.hpp"
#include "framework/core/penetration_depth.hpp"

namespace crowdlab {

std::vector<double> deepest_penetration_per_body(std::span<const WorldCapsules> bodies) {
  std::vector<Aabb> boxes(bodies.size());
  for (size_t i = 0; i < bodies.size(); ++i) boxes[i] = capsules_box(bodies[i]);
  std::vector<size_t> order(bodies.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return boxes[a].lo.x() < boxes[b].lo.x(); });
  std::vector<double> depth(bodies.size(), 0.0);
  for (size_t i = 0; i < order.size(); ++i) {
    const Aabb& a = boxes[order[i]];
    for (size_t j = i + 1; j < order.size() && boxes[order[j]].lo.x() <= a.hi.x(); ++j) {
      if (!a.overlaps(boxes[order[j]])) continue;
      const double d = max_penetration_depth(bodies[order[i]], bodies[order[j]]);
      depth[order[i]] = std::max(depth[order[i]], d);
      depth[order[j]] = std::max(depth[order[j]], d);
    }
  }
  return depth;
}

double deepest_crowd_penetration(std::span<const WorldCapsules> bodies) {
  const std::vector<double> per_body = deepest_penetration_per_body(bodies);
  return per_body.empty() ? 0.0 : *std::max_element(per_body.begin(), per_body.end());
}

}  // namespace crowdlab
