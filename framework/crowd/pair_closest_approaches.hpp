#pragma once
// Per frame and per pair of agents closer than max_distance_m: root distance, and time and distance
// to closest approach (seed 001 Eqs. 2-3, computed by core's closest_approach()) from the positions
// and the trajectories' finite-difference velocities (trajectory_velocity()).
// Pairs are listed once (i < j), frames in order, pairs sorted within a frame.
#include <functional>
#include <string>
#include <vector>

#include "framework/core/trajectories.hpp"

namespace crowdlab {

struct PairApproach {
  int frame = 0;
  int i = 0, j = 0;
  double distance_m = 0.0;  ///< current root distance
  double ttca_s = 0.0;      ///< +inf when the relative velocity is zero; negative when diverging
  double dtca_m = 0.0;
};

std::vector<PairApproach> pair_closest_approaches(const CrowdTrajectories& trajectories,
                                                  double max_distance_m);

/// CSV: frame,time_s,i,j,distance_m,ttca_s,dtca_m (ttca empty when infinite).
std::string pair_closest_approaches_csv(const std::vector<PairApproach>& rows, double fps);

/// Calls visit(i, j, distance) for every pair (i < j) closer than max_distance_m at `frame`,
/// in a deterministic order. Shared by the measures (uniform grid, O(N) per frame).
void for_each_close_pair(const CrowdTrajectories& trajectories, int frame, double max_distance_m,
                         const std::function<void(int, int, double)>& visit);

}  // namespace crowdlab
