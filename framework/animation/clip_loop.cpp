#include "framework/animation/clip_loop.hpp"

#include <cmath>
#include <string>

#include "framework/animation/rotation_helpers.hpp"
#include "framework/core/error.hpp"

namespace crowdlab {

namespace {
struct GroundFrame {
  Vec3 origin;  // root projected on the ground
  double heading;
};
GroundFrame ground_frame(const Pose& p) {
  return {Vec3(p.root_position_m.x(), 0, p.root_position_m.z()), p.heading_rad()};
}

// Applies the ground transform mapping `from` onto `to` to a pose.
Pose move_on_ground(const Pose& p, const GroundFrame& from, const GroundFrame& to) {
  const Quat turn = anim::yaw(to.heading - from.heading);
  Pose out = p;
  out.root_position_m = turn * (p.root_position_m - from.origin) + to.origin;
  out.local_rotations[0] = (turn * p.local_rotations[0]).normalized();
  return out;
}
}  // namespace

LoopedClip make_seamless_loop(const std::vector<Pose>& frames, int first, int last, int blend) {
  const int n = static_cast<int>(frames.size());
  if (first < 0 || last > n || blend < 0 || blend > first || first + blend >= last)
    throw InputError("make_seamless_loop: need 0 <= blend <= first, first + blend < last <= " +
                     std::to_string(n) + " (got first " + std::to_string(first) + ", last " +
                     std::to_string(last) + ", blend " + std::to_string(blend) + ")");
  // The pose that would follow the loop's last frame if the clip went on is frames[last]; the loop
  // restarts at frames[first]. D maps first's ground frame onto last's.
  const GroundFrame g_first = ground_frame(frames[static_cast<size_t>(first)]);
  const GroundFrame g_last = ground_frame(frames[static_cast<size_t>(std::min(last, n - 1))]);
  const GroundFrame g_end = last < n ? g_last : ground_frame(frames[static_cast<size_t>(last - 1)]);
  LoopedClip out;
  out.frames.assign(frames.begin() + first, frames.begin() + last);
  for (int k = last - blend; k < last; ++k) {
    const double w = anim::cosine_ease(static_cast<double>(k - (last - blend) + 1) / (blend + 1));
    const Pose& before = frames[static_cast<size_t>(first - (last - k))];
    const Pose moved = move_on_ground(before, g_first, g_end);
    out.frames[static_cast<size_t>(k - first)] = blend_poses(frames[static_cast<size_t>(k)], moved, w);
  }
  const Quat inv0 = anim::yaw(-g_first.heading);
  out.displacement = inv0 * (g_end.origin - g_first.origin);
  out.turn_rad = anim::wrap_angle(g_end.heading - g_first.heading);
  return out;
}

Pose sample_loop(const LoopedClip& loop, long k) {
  const long n = static_cast<long>(loop.frames.size());
  const long rep = k / n;
  const Pose& base = loop.frames[static_cast<size_t>(k % n)];
  // Accumulate `rep` loop displacements in the frame of frame 0.
  const GroundFrame g0 = ground_frame(loop.frames.front());
  GroundFrame g = g0;
  for (long r = 0; r < rep; ++r) {
    g.origin += anim::yaw(g.heading - g0.heading) * anim::yaw(g0.heading) * loop.displacement;
    g.heading += loop.turn_rad;
  }
  return move_on_ground(base, g0, g);
}

}  // namespace crowdlab
