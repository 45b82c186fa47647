#pragma once
// Dancing / idling in place for stationary crowds: one of the 16 looping motions of dance_motions.hpp
// per character, anchored on the character's 2D trajectory (which the crowd layer keeps almost
// still, with small sway and turns toward the stage).
//
// Per-character variation (DanceStyle, drawn from the character's seed): the motion, a tempo of
// 100-130 beats/min (typical of popular dance music; idle motions run at half tempo), a phase
// uniform over the whole loop, an amplitude of 0.75-1.25 and a left/right mirror, so neighbours are
// never in lock-step. When `fit_loops_to_s` > 0 the tempo is adjusted (by at most half a loop over
// the clip) so that a whole number of loops fits that duration: the clip then loops seamlessly too.
// Feet stay planted wherever the motion's lift is 0 (plant_foot_track + leg IK), and the pelvis is
// lowered where needed to keep both ankles reachable.
#include <array>
#include <cstdint>
#include <vector>

#include "framework/animation/foot_track.hpp"
#include "framework/core/body_shape.hpp"
#include "framework/core/pose.hpp"
#include "framework/core/trajectories.hpp"

namespace crowdlab {

struct DanceStyle {
  int motion = 0;  ///< index into dance_motions()
  double tempo_bpm = 118.0;
  double phase_beats = 0.0;  ///< beat offset at t = 0
  double amplitude = 1.0;
  bool mirror = false;
};

/// A style from the character's seed; `fit_loops_to_s` > 0 adjusts the tempo as described above.
DanceStyle dance_style_from_seed(std::uint64_t seed, double fit_loops_to_s = 0.0);

/// Loop period of a style in seconds.
double dance_loop_period_s(const DanceStyle& style);

using DanceResult = anim::GaitFrames;

/// Throws InputError for an empty / non-finite trajectory, fps <= 0 or a bad style.
DanceResult animate_dancing(const BodyShape& shape, const AgentTrajectory& anchor, double fps,
                            const DanceStyle& style);

}  // namespace crowdlab
