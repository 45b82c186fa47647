#pragma once
// A 2D trajectory prepared for gait synthesis (procedural walking and walking from clips): padded by
// 2 s of constant-velocity motion at both ends (so the first and last steps are complete), with
// smoothed speed, unwrapped smoothed heading and turn rate.
//   velocity: central differences averaged over +-0.15 s; heading: moving average over +-0.1 s;
//   end velocities: the mean over the first/last 0.2 s (one noisy sample does not set the padding).
#include <algorithm>
#include <string>
#include <vector>

#include "framework/animation/rotation_helpers.hpp"
#include "framework/core/trajectories.hpp"

namespace crowdlab::anim {

inline constexpr double kPadSeconds = 2.0;

struct PaddedTrack {
  int pad = 0;                    ///< padding frames before trajectory frame 0 (and after the last)
  std::vector<Vec2> pos;          ///< ground position (x, z), metres
  std::vector<double> heading;    ///< unwrapped, smoothed, radians
  std::vector<double> speed;      ///< smoothed, m/s
  std::vector<double> turn_rate;  ///< rad/s
};

PaddedTrack pad_and_smooth(const AgentTrajectory& t, double fps);

/// The checks every gait synthesiser makes at its boundary: fps > 0, one finite position and heading per
/// frame (at least one frame), and a reaction list that is empty or one weight per frame.
/// Throws InputError "<who>: <problem>".
void check_gait_inputs(const AgentTrajectory& t, double fps, const std::vector<double>& reaction,
                       const std::string& who);

/// How much a character walks at ground speed v: smoothstep over 0.05..0.25 m/s (0 standing, 1 walking).
inline double activity_of_speed(double v) {
  return smoothstep01((v - 0.05) / 0.20);
}

/// Centred moving average over +-r samples (truncated at the ends).
template <class T>
std::vector<T> moving_average(const std::vector<T>& x, int r) {
  std::vector<T> out(x.size());
  const auto n = static_cast<int>(x.size());
  for (int k = 0; k < n; ++k) {
    const int lo = std::max(0, k - r), hi = std::min(n - 1, k + r);
    T sum = x[static_cast<size_t>(lo)] * 0.0;
    for (int i = lo; i <= hi; ++i) sum += x[static_cast<size_t>(i)];
    out[static_cast<size_t>(k)] = sum / static_cast<double>(hi - lo + 1);
  }
  return out;
}

}  // namespace crowdlab::anim
