#include "framework/core/trajectories.hpp"

#include <algorithm>

namespace crowdlab {

Vec2 trajectory_velocity(const CrowdTrajectories& t, size_t agent, size_t frame) {
  const auto& p = t.agents[agent].position_m;
  if (p.size() < 2) return Vec2::Zero();
  const size_t lo = frame == 0 ? 0 : frame - 1;
  const size_t hi = std::min(frame + 1, p.size() - 1);
  return (p[hi] - p[lo]) * t.fps / static_cast<double>(hi - lo);
}

}  // namespace crowdlab
