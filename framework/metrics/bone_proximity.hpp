#pragma once
// Which bones of a crowd come near something else, frame by frame (issue 27): the contact scope
// behind the free-limb deviation (free_limb_deviation.hpp). Bone b of character c is NEAR on frame f
// when its capsule comes within margin_m of a capsule of another character or of an environment box
// (wall, barrier, stage; capsule_box_distance.hpp). The character's own capsules and the ground plane
// do not count: the input animation's own self-contacts and its feet on the floor are not collisions
// between characters, and the correction must leave them as they are. Triangle meshes in the
// environment are the ground surfaces of crowds on 3D surfaces (surface stage) and do not count either.
//
// Input: a crowd animation; output near[f][c], a bit mask over the 24 bones (bit b = bone b). Frames are
// measured in parallel (TBB), each frame serially: the result does not depend on the thread count.
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "framework/core/joint_scope.hpp"

namespace crowdlab {

/// near[f][c] for every frame f and character c; margin_m >= 0 (m).
std::vector<std::vector<BoneMask>> near_bones(const CrowdAnimation& crowd, double margin_m);

}  // namespace crowdlab
