#include "framework/surface/develop_surface_trajectories.hpp"

#include <cmath>

#include "framework/core/error.hpp"

namespace crowdlab {

CrowdTrajectories develop_surface_trajectories(const SurfaceTrajectories& surface, double fps,
                                               double radius_m) {
  CrowdTrajectories out;
  out.fps = fps;
  out.agents.resize(surface.agents.size());
  for (size_t i = 0; i < surface.agents.size(); ++i) {
    const SurfaceAgentTrajectory& s = surface.agents[i];
    const size_t frames = s.feet_m.size();
    if (s.up.size() != frames || s.forward.size() != frames)
      throw InputError("surface trajectories: agent " + std::to_string(i) + " has ragged per-frame arrays");
    AgentTrajectory& a = out.agents[i];
    a.radius_m = radius_m;
    a.position_m.resize(frames);
    a.heading_rad.resize(frames);
    for (size_t f = 0; f < frames; ++f) {
      if (!s.feet_m[f].allFinite() || !s.up[f].allFinite() || !s.forward[f].allFinite())
        throw InputError("surface trajectories: agent " + std::to_string(i) + " frame " + std::to_string(f) +
                         " is not finite");
      if (f == 0) {
        a.position_m[0] = Vec2::Zero();
        a.heading_rad[0] = 0.0;
        continue;
      }
      const Vec3& up = s.up[f];
      const Vec3 previous = s.forward[f - 1] - up * up.dot(s.forward[f - 1]);
      const double turn = std::atan2(up.dot(previous.cross(s.forward[f])), previous.dot(s.forward[f]));
      a.heading_rad[f] = a.heading_rad[f - 1] + turn;
      const double h = 0.5 * (a.heading_rad[f] + a.heading_rad[f - 1]);
      const double step = (s.feet_m[f] - s.feet_m[f - 1]).norm();
      a.position_m[f] = a.position_m[f - 1] + step * Vec2(std::sin(h), std::cos(h));
    }
  }
  return out;
}

}  // namespace crowdlab
