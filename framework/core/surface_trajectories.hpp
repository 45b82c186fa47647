#pragma once
// SurfaceTrajectories: the optional 3D companion of CrowdTrajectories for crowds that walk on a
// surface (scenario `manifold`, seed 002). CrowdTrajectories stays 2D: for a surface crowd it holds
// each agent's path DEVELOPED into the plane (same step lengths, same turning about the body's up
// axis, see develop_surface_trajectories), which is what the gait needs. This struct says where that
// planar motion happens in the world: per agent and frame, the point under the feet, the body's up
// vector and its facing direction. The animation stage maps each frame's pose from the developed
// plane onto this frame (orient_to_surface), so bodies stand along the surface normal on floors,
// walls and ceilings alike.
// Agents are in the same order as CrowdTrajectories::agents and have the same number of frames.
#include <string>
#include <vector>

#include "framework/core/math_types.hpp"

namespace crowdlab {

struct SurfaceAgentTrajectory {
  std::vector<Vec3> feet_m;   ///< (frames) point on the surface under the agent, world frame, metres
  std::vector<Vec3> up;       ///< (frames) unit body axis, feet to head (smoothed surface normal)
  std::vector<Vec3> forward;  ///< (frames) unit facing direction, tangent to the surface, orthogonal to up
};

struct SurfaceTrajectories {
  std::vector<SurfaceAgentTrajectory> agents;
  bool empty() const { return agents.empty(); }
};

/// CSV text, one row per agent per frame (metres, seconds, unit vectors in the world frame):
///   character,frame,time_s,x,y,z,up_x,up_y,up_z,forward_x,forward_y,forward_z
std::string surface_trajectories_csv(const SurfaceTrajectories& trajectories, double fps);

}  // namespace crowdlab
