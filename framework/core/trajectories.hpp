#pragma once
// CrowdTrajectories: the output of the crowd (global, 2D) layer and the input of the animation layer.
// Positions are on the ground plane: x and z world coordinates (metres); heading about +Y (radians,
// 0 faces +Z, pi/2 faces +X). Every agent has one sample per frame at `fps`.
#include <string>
#include <vector>

#include "framework/core/math_types.hpp"

namespace crowdlab {

struct AgentTrajectory {
  std::vector<Vec2> position_m;     ///< (frames) ground position (x, z), metres
  std::vector<double> heading_rad;  ///< (frames) facing direction
  double radius_m = 0.25;           ///< disc radius used by the navigation model
  int group = 0;                    ///< scenario-defined group (e.g. flow direction, focal character)
};

struct CrowdTrajectories {
  double fps = 30.0;
  std::vector<AgentTrajectory> agents;
  int frame_count() const { return agents.empty() ? 0 : static_cast<int>(agents.front().position_m.size()); }
};

/// CSV text, one row per agent per frame:
///   character,frame,time_s,x,z,heading_rad,group,radius_m   (metres, seconds, radians)
std::string trajectories_csv(const CrowdTrajectories& trajectories);

/// Velocity of agent `a` at frame f by central differences (one-sided at the ends), metres/second.
Vec2 trajectory_velocity(const CrowdTrajectories& t, size_t agent, size_t frame);

}  // namespace crowdlab
