#include "framework/animation/orient_to_surface.hpp"

#include <cmath>

#include "framework/core/error.hpp"

namespace crowdlab {
namespace {

Eigen::Matrix3d frame(const Vec3& up, const Vec3& forward) {
  Eigen::Matrix3d b;
  b.col(0) = up.cross(forward);
  b.col(1) = up;
  b.col(2) = forward;
  return b;
}

}  // namespace

void orient_to_surface(CrowdAnimation& crowd, const CrowdTrajectories& developed,
                       const SurfaceTrajectories& surface) {
  if (crowd.characters.size() != surface.agents.size() || developed.agents.size() != surface.agents.size())
    throw InputError("orient_to_surface: " + std::to_string(crowd.characters.size()) + " characters, " +
                     std::to_string(developed.agents.size()) + " developed and " +
                     std::to_string(surface.agents.size()) + " surface trajectories");
  for (size_t i = 0; i < surface.agents.size(); ++i) {
    CharacterAnimation& c = crowd.characters[i];
    const SurfaceAgentTrajectory& s = surface.agents[i];
    const AgentTrajectory& d = developed.agents[i];
    if (c.frames.size() != s.feet_m.size() || d.position_m.size() != s.feet_m.size() ||
        s.up.size() != s.feet_m.size() || s.forward.size() != s.feet_m.size())
      throw InputError("orient_to_surface: character " + c.name + " has mismatched frame counts");
    for (size_t f = 0; f < c.frames.size(); ++f) {
      const Vec3& n = s.up[f];
      const Vec3& t = s.forward[f];
      if (std::abs(n.norm() - 1) > 1e-6 || std::abs(t.norm() - 1) > 1e-6 || std::abs(n.dot(t)) > 1e-6)
        throw InputError("orient_to_surface: character " + c.name + " frame " + std::to_string(f) +
                         ": up and forward must be orthonormal");
      const double h = d.heading_rad[f];
      const Eigen::Matrix3d M =
          frame(n, t) * frame(Vec3::UnitY(), Vec3(std::sin(h), 0, std::cos(h))).transpose();
      Pose& pose = c.frames[f];
      const Vec3 origin(d.position_m[f].x(), 0, d.position_m[f].y());
      pose.root_position_m = s.feet_m[f] + M * (pose.root_position_m - origin);
      pose.local_rotations[0] = (Quat(M) * pose.local_rotations[0]).normalized();
    }
  }
}

}  // namespace crowdlab
