#pragma once
// Deepest interpenetration of two posed bodies (their world capsules, metres): the maximum over capsule
// pairs (one from each) of r_a + r_b - distance between their axes, clamped at 0. Broad phase as in seed
// 000 §3.4 ("Culling"): body AABBs first, then each capsule's bounding sphere against the other body's box.
// Used by the metrics (character_overlap.hpp) and by the correction's loop closure (correct_crowd.hpp).
#include "framework/core/forward_kinematics.hpp"

namespace crowdlab {

double max_penetration_depth(const WorldCapsules& a, const WorldCapsules& b);

}  // namespace crowdlab
