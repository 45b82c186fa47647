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
  // Sample the continued loop once over [c - w, c + n + w) (c far enough into the replays that every
  // index is >= 0), then slide the +-w window with running sums: O(n + w).
  const long c = n * (1 + w / n);
  std::vector<Pose> seq;
  seq.reserve(static_cast<size_t>(n + 2 * w));
  for (long i = c - w; i < c + n + w; ++i) seq.push_back(sample_loop(loop, i));
  std::vector<double> unwrapped(seq.size());
  for (size_t i = 0; i < seq.size(); ++i)
    unwrapped[i] = i == 0 ? seq[0].heading_rad()
                          : unwrapped[i - 1] + anim::wrap_angle(seq[i].heading_rad() - unwrapped[i - 1]);
  Vec3 sum_pos = Vec3::Zero();
  double sum_heading = 0;
  for (long i = 0; i < 2 * w + 1; ++i) {
    sum_pos += Vec3(seq[static_cast<size_t>(i)].root_position_m.x(), 0,
                    seq[static_cast<size_t>(i)].root_position_m.z());
    sum_heading += unwrapped[static_cast<size_t>(i)];
  }
  std::vector<Pose> local(static_cast<size_t>(n));
  const double count = static_cast<double>(2 * w + 1);
  for (long k = 0; k < n; ++k) {
    if (k > 0) {  // slide: drop k - 1, add k + 2w
      const Pose& drop = seq[static_cast<size_t>(k - 1)];
      const Pose& add = seq[static_cast<size_t>(k + 2 * w)];
      sum_pos += Vec3(add.root_position_m.x() - drop.root_position_m.x(), 0,
                      add.root_position_m.z() - drop.root_position_m.z());
      sum_heading += unwrapped[static_cast<size_t>(k + 2 * w)] - unwrapped[static_cast<size_t>(k - 1)];
    }
    const Pose& centre = seq[static_cast<size_t>(k + w)];
    const Vec3 mean = sum_pos / count;
    // Express the pose relative to (mean position, mean heading).
    const Quat unturn = anim::yaw(-sum_heading / count);
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
