#include "framework/animation/smoothed_track.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/error.hpp"

namespace crowdlab::anim {

void check_gait_inputs(const AgentTrajectory& t, double fps, const std::vector<double>& reaction,
                       const std::string& who) {
  const size_t n = t.position_m.size();
  if (!(fps > 0) || !std::isfinite(fps)) throw InputError(who + ": fps must be > 0");
  if (n == 0 || t.heading_rad.size() != n)
    throw InputError(who + ": trajectory needs one position and heading per frame (got " + std::to_string(n) +
                     " and " + std::to_string(t.heading_rad.size()) + ")");
  for (size_t k = 0; k < n; ++k)
    if (!t.position_m[k].allFinite() || !std::isfinite(t.heading_rad[k]))
      throw InputError(who + ": trajectory frame " + std::to_string(k) + " is not finite");
  if (!reaction.empty() && reaction.size() != n) throw InputError(who + ": reaction size mismatch");
}

PaddedTrack pad_and_smooth(const AgentTrajectory& t, double fps) {
  const auto n = static_cast<int>(t.position_m.size());
  PaddedTrack p;
  p.pad = static_cast<int>(std::lround(kPadSeconds * fps));
  const int m = n + 2 * p.pad;
  auto vel_at = [&](int k) -> Vec2 {
    if (n < 2) return Vec2::Zero();
    const int lo = std::max(0, k - 1), hi = std::min(n - 1, k + 1);
    return (t.position_m[static_cast<size_t>(hi)] - t.position_m[static_cast<size_t>(lo)]) * fps / (hi - lo);
  };
  // Average the end velocities over 0.2 s so one noisy sample does not set the padding.
  const int w = std::max(1, static_cast<int>(0.2 * fps));
  Vec2 v0 = Vec2::Zero(), v1 = Vec2::Zero();
  for (int i = 0; i < w; ++i) v0 += vel_at(std::min(i, n - 1)) / w, v1 += vel_at(std::max(n - 1 - i, 0)) / w;
  std::vector<double> unwrapped(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double h = t.heading_rad[static_cast<size_t>(k)];
    unwrapped[static_cast<size_t>(k)] = k == 0 ? h
                                               : unwrapped[static_cast<size_t>(k - 1)] +
                                                     wrap_angle(h - unwrapped[static_cast<size_t>(k - 1)]);
  }
  p.pos.resize(static_cast<size_t>(m));
  std::vector<double> heading(static_cast<size_t>(m));
  for (int k = 0; k < m; ++k) {
    const int f = k - p.pad;
    if (f < 0) {
      p.pos[static_cast<size_t>(k)] = t.position_m.front() + v0 * (f / fps);
      heading[static_cast<size_t>(k)] = unwrapped.front();
    } else if (f >= n) {
      p.pos[static_cast<size_t>(k)] = t.position_m.back() + v1 * ((f - n + 1) / fps);
      heading[static_cast<size_t>(k)] = unwrapped.back();
    } else {
      p.pos[static_cast<size_t>(k)] = t.position_m[static_cast<size_t>(f)];
      heading[static_cast<size_t>(k)] = unwrapped[static_cast<size_t>(f)];
    }
  }
  const int r = std::max(1, static_cast<int>(std::lround(0.15 * fps)));
  std::vector<Vec2> vel(static_cast<size_t>(m));
  for (int k = 0; k < m; ++k) {
    const int lo = std::max(0, k - 1), hi = std::min(m - 1, k + 1);
    vel[static_cast<size_t>(k)] =
        (p.pos[static_cast<size_t>(hi)] - p.pos[static_cast<size_t>(lo)]) * fps / std::max(1, hi - lo);
  }
  vel = moving_average(vel, r);
  p.speed.resize(static_cast<size_t>(m));
  for (int k = 0; k < m; ++k) p.speed[static_cast<size_t>(k)] = vel[static_cast<size_t>(k)].norm();
  p.heading = moving_average(heading, std::max(1, static_cast<int>(std::lround(0.1 * fps))));
  p.turn_rate.resize(static_cast<size_t>(m));
  for (int k = 0; k < m; ++k) {
    const int lo = std::max(0, k - 1), hi = std::min(m - 1, k + 1);
    p.turn_rate[static_cast<size_t>(k)] =
        (p.heading[static_cast<size_t>(hi)] - p.heading[static_cast<size_t>(lo)]) * fps /
        std::max(1, hi - lo);
  }
  p.turn_rate = moving_average(p.turn_rate, r);
  return p;
}

}  // namespace crowdlab::anim
