#include "framework/core/trajectories.hpp"

#include <algorithm>

#include "framework/core/csv.hpp"

namespace crowdlab {

Vec2 trajectory_velocity(const CrowdTrajectories& t, size_t agent, size_t frame) {
  const auto& p = t.agents[agent].position_m;
  if (p.size() < 2) return Vec2::Zero();
  const size_t lo = frame == 0 ? 0 : frame - 1;
  const size_t hi = std::min(frame + 1, p.size() - 1);
  return (p[hi] - p[lo]) * t.fps / static_cast<double>(hi - lo);
}

std::string trajectories_csv(const CrowdTrajectories& t) {
  std::string s = csv_line({"character", "frame", "time_s", "x", "z", "heading_rad", "group", "radius_m"});
  for (std::size_t i = 0; i < t.agents.size(); ++i) {
    const AgentTrajectory& a = t.agents[i];
    for (std::size_t f = 0; f < a.position_m.size(); ++f)
      s += csv_line({std::to_string(i), std::to_string(f), csv_number(static_cast<double>(f) / t.fps),
                     csv_number(a.position_m[f].x()), csv_number(a.position_m[f].y()),
                     csv_number(a.heading_rad[f]), std::to_string(a.group), csv_number(a.radius_m)});
  }
  return s;
}

}  // namespace crowdlab
