#pragma once
// Environment penetration (issue 27; seed 000 §3.4 lists body-environment contact as one of its four
// collision types): how deep the capsule bodies go behind a wall, barrier or stage surface.
//
// For every frame, character and bone, the depth of its capsule behind each environment box is
// max(0, -capsule_box_distance) (capsule_box_distance.hpp: the deepest point of the capsule behind the
// box surface, exact). Reported: p99 (nearest rank) and max over the positive depths, how many there
// were, and where the max is. Triangle meshes in the environment are ground surfaces (surface stage) and
// are not measured here; the ground plane is the feet's (foot_contact_quality.hpp).
#include "framework/core/crowd_animation.hpp"

namespace crowdlab {

struct EnvironmentPenetration {
  double p99_m = 0.0;
  double max_m = 0.0;
  long samples = 0;                                             ///< capsule-box-frame depths > 0
  int worst_character = -1, worst_bone = -1, worst_frame = -1;  ///< where max_m is (-1: none)
};

/// Frames from first_frame on (0 = all).
EnvironmentPenetration measure_environment_penetration(const CrowdAnimation& crowd, int first_frame = 0);

}  // namespace crowdlab
