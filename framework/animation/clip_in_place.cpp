#include "framework/animation/clip_in_place.hpp"

#include <cmath>

#include "framework/animation/rotation_helpers.hpp"
#include "framework/core/error.hpp"

namespace crowdlab {

std::vector<Pose> play_clip_in_place(const LoopedClip& loop, double clip_fps, const AgentTrajectory& anchor,
                                     double fps, double offset_s) {
  if (loop.frames.empty() || !(clip_fps > 0) || !(fps > 0))
    throw InputError("play_clip_in_place: empty loop or fps <= 0");
  const auto n = static_cast<long>(loop.frames.size());
  const long w = std::max(1L, std::lround(clip_fps));  // +-1 s window
  // Clip frames with their ground deviation from the moving average, over one loop (sampled from
  // the continued loop so the window wraps across replays seamlessly).
  std::vector<Pose> local(static_cast<size_t>(n));
  for (long k = 0; k < n; ++k) {
    const long c = k + n * (1 + w / n);  // far enough into the replays that k - w >= 0
    Vec3 mean = Vec3::Zero();
    double heading_sum = 0;
    const Pose centre = sample_loop(loop, c);
    const double h_c = centre.heading_rad();
    for (long i = c - w; i <= c + w; ++i) {
      const Pose p = sample_loop(loop, i);
      mean += Vec3(p.root_position_m.x(), 0, p.root_position_m.z());
      heading_sum += anim::wrap_angle(p.heading_rad() - h_c);
    }
    mean /= static_cast<double>(2 * w + 1);
    const double mean_heading = h_c + heading_sum / static_cast<double>(2 * w + 1);
    // Express the pose relative to (mean position, mean heading).
    const Quat unturn = anim::yaw(-mean_heading);
    Pose p = centre;
    p.root_position_m = unturn * (centre.root_position_m - mean);
    p.local_rotations[0] = (unturn * centre.local_rotations[0]).normalized();
    local[static_cast<size_t>(k)] = p;
  }
  std::vector<Pose> out(anchor.position_m.size());
  for (size_t f = 0; f < out.size(); ++f) {
    const double x = (static_cast<double>(f) / fps + offset_s) * clip_fps;
    const double base = std::floor(x);
    const long k0 = ((static_cast<long>(base) % n) + n) % n;
    const long k1 = (k0 + 1) % n;
    Pose p = blend_poses(local[static_cast<size_t>(k0)], local[static_cast<size_t>(k1)], x - base);
    const Quat turn = anim::yaw(anchor.heading_rad[f]);
    p.root_position_m =
        turn * p.root_position_m + Vec3(anchor.position_m[f].x(), 0, anchor.position_m[f].y());
    p.local_rotations[0] = (turn * p.local_rotations[0]).normalized();
    out[f] = p;
  }
  return out;
}

}  // namespace crowdlab
