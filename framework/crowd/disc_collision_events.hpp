#pragma once
// Collision events between agent discs: a collision is counted when a pair STARTS overlapping
// (centre distance < r_i + r_j), so a pair that stays in contact for many frames counts once, and
// a pair overlapping in the first frame counts once. This is the count of seed 001's Table 2
// ("number of collisions detected by our system"), here on the navigation discs.
#include <string>
#include <vector>

#include "framework/core/trajectories.hpp"

namespace crowdlab {

struct CollisionEvent {
  int i = 0, j = 0;              ///< i < j
  int start_frame = 0;           ///< first overlapping frame
  int end_frame = 0;             ///< first frame no longer overlapping (frame_count if never)
  double max_penetration_m = 0;  ///< largest r_i + r_j - distance during the event
};

/// Events ordered by start frame, then (i, j).
std::vector<CollisionEvent> disc_collision_events(const CrowdTrajectories& trajectories);

/// CSV: i,j,start_frame,end_frame,start_time_s,duration_s,max_penetration_m.
std::string disc_collision_events_csv(const std::vector<CollisionEvent>& events, double fps);

}  // namespace crowdlab
