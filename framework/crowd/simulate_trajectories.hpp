#pragma once
// Runs a CrowdSimulation for a clip and resamples it to the clip's frame rate.
//   frames: round(duration_s * fps) (at least 1); frame f is at t = f / fps.
//   position: linear interpolation between simulation steps (the simulation's own dt).
//   heading: direction of the velocity averaged over a 0.4 s window centred on t (positions at
//            t +- 0.2 s), so the facing does not flicker with step-to-step velocity noise; while the
//            agent is nearly still (< 0.05 m/s) the previous heading is kept. Heading 0 faces +Z
//            (the simulation's +y) and pi/2 faces +X: heading = atan2(v_x, v_z). Unwrapped (no 2 pi
//            jumps between frames).
#include <cmath>
#include <vector>

#include "framework/core/trajectories.hpp"
#include "framework/crowd/crowd_simulation.hpp"

namespace crowdlab {

/// initial_heading_rad / group: one per agent (the heading used before the agent first moves).
CrowdTrajectories simulate_trajectories(CrowdSimulation& sim, double duration_s, double fps,
                                        const std::vector<double>& initial_heading_rad,
                                        const std::vector<int>& group);

/// Heading (radians, 0 = +Z, pi/2 = +X) of a ground-plane direction (x, z).
inline double heading_of(double x, double z) {
  return std::atan2(x, z);
}

}  // namespace crowdlab
