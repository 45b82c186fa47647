#include "framework/core/joint_flips.hpp"

#include <algorithm>

#include "framework/core/rotation_angle.hpp"

namespace crowdlab {

JointFlips measure_joint_flips(const CrowdAnimation& input, const CrowdAnimation& corrected,
                               int first_frame) {
  JointFlips q;
  const int frames = input.frame_count();
  const int first = std::max(0, first_frame);
  std::vector<Quat> dev(static_cast<size_t>(std::max(0, frames)));
  for (size_t c = 0; c < input.characters.size(); ++c)
    for (int j = 0; j < kJointCount; ++j) {
      for (int f = first; f < frames; ++f) {
        const auto jj = static_cast<size_t>(j), ff = static_cast<size_t>(f);
        dev[ff] = input.characters[c].frames[ff].local_rotations[jj].normalized().conjugate() *
                  corrected.characters[c].frames[ff].local_rotations[jj].normalized();
        double change = 0.0;
        for (int k = 1; k <= kFlipFrames && f - k >= first; ++k)
          change = std::max(change, rotation_angle_deg(dev[static_cast<size_t>(f - k)], dev[ff]));
        q.max_change_deg = std::max(q.max_change_deg, change);
        if (!(change > kFlipAngle_deg)) continue;
        ++q.count;
        ++q.per_joint[static_cast<size_t>(j)];
        if (q.first.size() < kListedFlips) q.first.push_back({static_cast<int>(c), j, f, change});
      }
    }
  return q;
}

}  // namespace crowdlab
