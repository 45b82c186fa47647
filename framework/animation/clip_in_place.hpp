#pragma once
// Playing a looped motion clip (e.g. a retargeted BVH dance) in place on a stationary character.
//
// The clip's own ground travel is removed: its root ground position is replaced by the anchor's plus
// the clip's deviation from its own moving average over +-1 s (so hip sway and small steps remain,
// wandering across the floor does not), and its heading by the anchor's plus the deviation from the
// clip's moving-average heading. Time is resampled from the clip's fps to the output fps with linear
// root / slerp rotation interpolation; the character starts `offset_s` into the loop.
// Note: feet are not re-planted after this change, so a dancer that travels in the source clip
// slides a little; the procedural dances (dance_animation.hpp) have no such skate.
#include <vector>

#include "framework/animation/clip_loop.hpp"
#include "framework/core/trajectories.hpp"

namespace crowdlab {

/// loop: a seamless loop at clip_fps. Returns one pose per anchor frame (at fps).
std::vector<Pose> play_clip_in_place(const LoopedClip& loop, double clip_fps, const AgentTrajectory& anchor,
                                     double fps, double offset_s);

}  // namespace crowdlab
