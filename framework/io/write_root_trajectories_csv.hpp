#pragma once
// CSV export of the characters' root trajectories on the ground plane.
#include <string>

#include "framework/core/crowd_animation.hpp"

namespace crowdlab {

/// Writes one row per character per frame, characters in crowd order, frames in time order:
///   character,frame,time_s,x,z,heading_rad
/// character: the character's name; frame: 0-based; time_s = frame / fps (seconds); x, z: the root
/// (pelvis) position on the ground plane (metres, world frame); heading_rad: Pose::heading_rad(),
/// the root's facing about +Y (0 = +Z, pi/2 = +X), in (-pi, pi]. Numbers use shortest round-trip text.
/// Validates the crowd first (InputError); throws RuntimeError when the file cannot be written.
void write_root_trajectories_csv(const CrowdAnimation& crowd, const std::string& path);

}  // namespace crowdlab
