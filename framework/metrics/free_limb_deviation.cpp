#include "framework/metrics/free_limb_deviation.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/frame_in_loop.hpp"
#include "framework/core/rotation_angle.hpp"
#include "framework/metrics/bone_proximity.hpp"
#include "framework/metrics/correction_quality.hpp"

namespace crowdlab {

FreeLimbDeviation measure_free_limb_deviation(const CrowdAnimation& input, const CrowdAnimation& corrected,
                                              int first_frame, bool looped, double margin_m,
                                              double window_s) {
  FreeLimbDeviation q;
  const int frames = input.frame_count();
  const int first = std::max(0, first_frame);
  if (frames <= first) return q;
  const auto near_in = near_bones(input, margin_m);
  const auto near_out = near_bones(corrected, margin_m);
  const int w = static_cast<int>(std::lround(window_s * input.meta.fps));
  std::array<std::uint32_t, kJointCount> scope{};
  for (int j = 0; j < kJointCount; ++j) scope[static_cast<size_t>(j)] = contact_scope(j);

  std::vector<double> samples;
  for (size_t c = 0; c < input.characters.size(); ++c)
    for (int j = 0; j < kJointCount; ++j) {
      // busy(g): the scope is near something on frame g, which may lie outside the clip: around the loop
      // when it loops, never otherwise. last_busy: the latest such g <= f + w.
      auto busy = [&](int g) {
        if (looped)
          g = frame_in_loop(g, frames);
        else if (g < 0 || g >= frames)
          return false;
        const std::uint32_t m = near_in[static_cast<size_t>(g)][c] | near_out[static_cast<size_t>(g)][c];
        return (m & scope[static_cast<size_t>(j)]) != 0;
      };
      int last_busy = -1 - 2 * w;
      for (int g = -w; g < w; ++g)
        if (busy(g)) last_busy = g;
      for (int f = 0; f < frames; ++f) {
        if (busy(f + w)) last_busy = f + w;
        if (f < first) continue;
        ++q.joint_frames;
        if (last_busy >= f - w) continue;
        ++q.free_joint_frames;
        const double d = rotation_angle_deg(
            input.characters[c].frames[static_cast<size_t>(f)].local_rotations[static_cast<size_t>(j)],
            corrected.characters[c].frames[static_cast<size_t>(f)].local_rotations[static_cast<size_t>(j)]);
        samples.push_back(d);
        if (d > q.max_deg) {
          q.max_deg = d;
          q.worst_character = static_cast<int>(c);
          q.worst_joint = j;
          q.worst_frame = f;
        }
      }
    }
  q.p99_deg = nearest_rank_quantile(std::move(samples), 0.99);
  return q;
}

}  // namespace crowdlab
