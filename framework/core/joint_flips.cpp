#include "framework/core/joint_flips.hpp"

#include <algorithm>

#include <cmath>
#include <string>

#include "framework/core/error.hpp"
#include "framework/core/frame_in_loop.hpp"
#include "framework/core/rotation_angle.hpp"

namespace crowdlab {

FlipWindow flip_window(double fps) {
  if (!std::isfinite(fps) || fps <= 0.0)
    throw InputError("joint flips: frame rate " + std::to_string(fps) + " fps is not positive");
  FlipWindow w;
  w.frames = std::max(1, static_cast<int>(std::lround(kFlipWindow_s * fps)));
  w.angle_deg = kFlipRate_degps * w.frames / fps;
  return w;
}

JointFlips measure_joint_flips(const CrowdAnimation& input, const CrowdAnimation& corrected, int first_frame,
                               bool looped) {
  JointFlips q;
  const FlipWindow window = flip_window(corrected.meta.fps);
  const int frames = input.frame_count();
  const int first = std::max(0, first_frame);
  std::vector<Quat> dev(static_cast<size_t>(std::max(0, frames)));
  for (size_t c = 0; c < input.characters.size(); ++c)
    for (int j = 0; j < kJointCount; ++j) {
      const auto jj = static_cast<size_t>(j);
      for (int f = looped ? 0 : first; f < frames; ++f) {
        const auto ff = static_cast<size_t>(f);
        dev[ff] = input.characters[c].frames[ff].local_rotations[jj].normalized().conjugate() *
                  corrected.characters[c].frames[ff].local_rotations[jj].normalized();
      }
      for (int f = first; f < frames; ++f) {
        const auto ff = static_cast<size_t>(f);
        double change = 0.0;
        for (int k = 1; k <= window.frames; ++k) {
          // The frame k before f: around the loop when the clip loops, else only counted frames.
          int g = f - k;
          if (looped)
            g = frame_in_loop(g, frames);
          else if (g < first)
            break;
          change = std::max(change, rotation_angle_deg(dev[static_cast<size_t>(g)], dev[ff]));
        }
        q.max_change_deg = std::max(q.max_change_deg, change);
        if (!(change > window.angle_deg)) continue;
        ++q.count;
        ++q.per_joint[static_cast<size_t>(j)];
        if (q.first.size() < kListedFlips) q.first.push_back({static_cast<int>(c), j, f, change});
      }
    }
  return q;
}

}  // namespace crowdlab
