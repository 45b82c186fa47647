#pragma once
// Set dressing: what a participant sees around the crowd that the simulation does not need, per scenario
// (CrowdAnimation::meta.scenario). Drawn by the renderer only: it casts no shadow, is cut away like the
// environment's boxes when it stands between the camera and a character (frame_plan.hpp), and is neither
// written to crowd files nor seen by the collision corrector.
//   stationary (a concert, seed 000 §4.4.1): the stage is the environment's first box; behind it a back
//     wall with a dark backdrop, a lighting truss above the stage front with six coloured lamps; around the
//     crowd a hall: a back wall behind the crowd and side walls 9 m either side of the crowd's axis, with
//     warm wall lamps and a green exit sign, so that a front view (V1, looking from the stage) shows a
//     venue behind the dancers rather than an empty horizon.
//   corridor: each barrier (the environment's boxes) is backed by a 2.6 m plaster wall 0.15 m outside it,
//     with a dark skirting and pilasters every 3 m (they make the walking speed readable), and ceiling-height
//     lamps along both walls.
// Sizes are those of a small club and an indoor passage (no published standard; chosen on rendered frames).
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "stimuli/palette.hpp"

namespace crowdlab::stimuli {

struct DecorBox {
  Box box;
  Rgb colour = {0.5f, 0.5f, 0.5f};  ///< sRGB
  float emission = 0.0f;            ///< 0: lit like any surface; 1: a lamp, drawn at its own colour
};

/// The set for `crowd`'s scenario around the crowd's clip-wide bounds (metres); empty for other scenarios
/// (pair crossing, flows, manifolds, synthetic crowds) or when the scenario's environment is missing.
std::vector<DecorBox> make_scene_set(const CrowdAnimation& crowd, const Vec3& bounds_lo,
                                     const Vec3& bounds_hi);

}  // namespace crowdlab::stimuli
