#include "framework/metrics/environment_penetration.hpp"

#include <algorithm>

#include <tbb/parallel_for.h>

#include "framework/core/capsule_box.hpp"
#include "framework/core/capsule_box_distance.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/metrics/correction_quality.hpp"

namespace crowdlab {
namespace {

struct Depth {
  double depth_m;
  int character, bone;
};

std::vector<Depth> frame_depths(const CrowdAnimation& crowd, int f, const std::vector<Aabb>& bounds) {
  std::vector<Depth> out;
  for (size_t c = 0; c < crowd.characters.size(); ++c) {
    const CharacterAnimation& ch = crowd.characters[c];
    const WorldCapsules caps = world_capsules(ch.shape, ch.frames[static_cast<size_t>(f)]);
    for (int b = 0; b < kJointCount; ++b) {
      const Capsule& cap = caps[static_cast<size_t>(b)];
      const Aabb box = capsule_box(cap);
      for (size_t k = 0; k < bounds.size(); ++k) {
        if (!box.overlaps(bounds[k])) continue;
        const double d = -capsule_box_distance(cap, crowd.environment.boxes[k]).distance_m;
        if (d > 0.0) out.push_back({d, static_cast<int>(c), b});
      }
    }
  }
  return out;
}

}  // namespace

EnvironmentPenetration measure_environment_penetration(const CrowdAnimation& crowd, int first_frame) {
  EnvironmentPenetration q;
  const int frames = crowd.frame_count();
  const int first = std::max(0, first_frame);
  if (crowd.environment.boxes.empty() || frames <= first) return q;
  std::vector<Aabb> bounds;
  for (const Box& b : crowd.environment.boxes) bounds.push_back(box_bounds(b));
  std::vector<std::vector<Depth>> per_frame(static_cast<size_t>(frames - first));
  tbb::parallel_for(first, frames, [&](int f) {
    per_frame[static_cast<size_t>(f - first)] = frame_depths(crowd, f, bounds);
  });
  std::vector<double> depths;
  for (size_t i = 0; i < per_frame.size(); ++i)
    for (const Depth& d : per_frame[i]) {
      depths.push_back(d.depth_m);
      if (d.depth_m > q.max_m) {
        q.max_m = d.depth_m;
        q.worst_character = d.character;
        q.worst_bone = d.bone;
        q.worst_frame = first + static_cast<int>(i);
      }
    }
  q.samples = static_cast<long>(depths.size());
  q.p99_m = nearest_rank_quantile(std::move(depths), 0.99);
  return q;
}

}  // namespace crowdlab
