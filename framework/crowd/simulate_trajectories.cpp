#include "framework/crowd/simulate_trajectories.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "framework/core/error.hpp"

namespace crowdlab {
namespace {
double wrap_pi(double a) {
  return std::remainder(a, 2.0 * std::numbers::pi);
}
}  // namespace

CrowdTrajectories simulate_trajectories(CrowdSimulation& sim, double duration_s, double fps,
                                        const std::vector<double>& initial_heading,
                                        const std::vector<int>& group) {
  if (!(fps > 0.0) || !std::isfinite(fps)) throw InputError("fps: must be > 0");
  if (!(duration_s > 0.0) || !std::isfinite(duration_s)) throw InputError("duration_s: must be > 0");
  const std::size_t n = sim.size();
  if (initial_heading.size() != n || group.size() != n)
    throw InputError("simulate_trajectories: one initial heading and group per agent required");
  const int frames = std::max(1, static_cast<int>(std::lround(duration_s * fps)));
  const double dt = sim.dt_s();
  const double window = 0.2;  // s, half-width of the heading window
  const double t_end = (frames - 1) / fps + window;
  const int steps = static_cast<int>(std::ceil(t_end / dt)) + 1;
  // Recorded positions at t = k dt, k = 0..steps (agent-major).
  std::vector<std::vector<Vec2>> rec(n, std::vector<Vec2>(static_cast<std::size_t>(steps) + 1));
  for (std::size_t i = 0; i < n; ++i) rec[i][0] = sim.position(i);
  for (int k = 1; k <= steps; ++k) {
    sim.step();
    for (std::size_t i = 0; i < n; ++i) rec[i][static_cast<std::size_t>(k)] = sim.position(i);
  }
  auto at = [&](std::size_t i, double t) -> Vec2 {
    const double u = std::clamp(t / dt, 0.0, static_cast<double>(steps));
    const auto k = std::min(static_cast<std::size_t>(u), static_cast<std::size_t>(steps) - 1);
    const double f = u - static_cast<double>(k);
    return (1.0 - f) * rec[i][k] + f * rec[i][k + 1];
  };
  CrowdTrajectories out;
  out.fps = fps;
  out.agents.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    AgentTrajectory& a = out.agents[i];
    a.radius_m = sim.radius(i);
    a.group = group[i];
    a.position_m.resize(static_cast<std::size_t>(frames));
    a.heading_rad.resize(static_cast<std::size_t>(frames));
    double heading = initial_heading[i];
    for (int f = 0; f < frames; ++f) {
      const double t = f / fps;
      a.position_m[static_cast<std::size_t>(f)] = at(i, t);
      const double t0 = std::max(0.0, t - window), t1 = t + window;
      const Vec2 v = (at(i, t1) - at(i, t0)) / (t1 - t0);
      if (v.norm() >= 0.05) heading += wrap_pi(heading_of(v.x(), v.y()) - heading);
      a.heading_rad[static_cast<std::size_t>(f)] = heading;
    }
  }
  return out;
}

}  // namespace crowdlab
