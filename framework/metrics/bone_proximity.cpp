#include "framework/metrics/bone_proximity.hpp"

#include <tbb/parallel_for.h>

#include "framework/core/capsule_box.hpp"
#include "framework/core/capsule_box_distance.hpp"
#include "framework/core/forward_kinematics.hpp"

namespace crowdlab {
namespace {

/// Marks in near_i / near_j the capsules of two posed bodies within margin of each other.
void mark_pair(const WorldCapsules& ci, const WorldCapsules& cj, const std::array<Aabb, kJointCount>& bi,
               const std::array<Aabb, kJointCount>& bj, double margin, BoneMask& near_i, BoneMask& near_j) {
  for (int a = 0; a < kJointCount; ++a)
    for (int b = 0; b < kJointCount; ++b) {
      const BoneMask ma = BoneMask{1} << a, mb = BoneMask{1} << b;
      if ((near_i & ma) && (near_j & mb)) continue;  // both already known near
      if (!bi[static_cast<size_t>(a)].overlaps(bj[static_cast<size_t>(b)])) continue;
      if (capsule_contact(ci[static_cast<size_t>(a)], cj[static_cast<size_t>(b)]).depth_m > -margin) {
        near_i |= ma;
        near_j |= mb;
      }
    }
}

std::vector<BoneMask> near_in_frame(const CrowdAnimation& crowd, int f, double margin,
                                    const std::vector<Aabb>& env_boxes) {
  const size_t n = crowd.characters.size();
  std::vector<WorldCapsules> caps(n);
  std::vector<std::array<Aabb, kJointCount>> boxes(n);  // capsule boxes grown by margin / 2
  std::vector<Aabb> body(n);
  for (size_t c = 0; c < n; ++c) {
    const CharacterAnimation& ch = crowd.characters[c];
    caps[c] = world_capsules(ch.shape, ch.frames[static_cast<size_t>(f)]);
    for (size_t b = 0; b < kJointCount; ++b) {
      boxes[c][b] = capsule_box(caps[c][b], 0.5 * margin);
      body[c].extend(boxes[c][b]);
    }
  }
  std::vector<BoneMask> near(n, 0);
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 1; j < n; ++j)
      if (body[i].overlaps(body[j]))
        mark_pair(caps[i], caps[j], boxes[i], boxes[j], margin, near[i], near[j]);
    for (size_t k = 0; k < env_boxes.size(); ++k) {
      if (!body[i].overlaps(env_boxes[k])) continue;
      for (int b = 0; b < kJointCount; ++b)
        if (boxes[i][static_cast<size_t>(b)].overlaps(env_boxes[k]) &&
            capsule_box_distance(caps[i][static_cast<size_t>(b)], crowd.environment.boxes[k]).distance_m <
                margin)
          near[i] |= BoneMask{1} << b;
    }
  }
  return near;
}

}  // namespace

std::vector<std::vector<BoneMask>> near_bones(const CrowdAnimation& crowd, double margin_m) {
  const int frames = crowd.frame_count();
  std::vector<Aabb>
      env_boxes;  // the boxes' bounds grown by half the margin (the capsules' by the other half)
  for (const Box& b : crowd.environment.boxes) {
    Aabb box = box_bounds(b);
    box.lo.array() -= 0.5 * margin_m;
    box.hi.array() += 0.5 * margin_m;
    env_boxes.push_back(box);
  }
  std::vector<std::vector<BoneMask>> near(static_cast<size_t>(std::max(0, frames)));
  tbb::parallel_for(
      0, frames, [&](int f) { near[static_cast<size_t>(f)] = near_in_frame(crowd, f, margin_m, env_boxes); });
  return near;
}

}  // namespace crowdlab
