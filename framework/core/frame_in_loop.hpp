#pragma once
// frame_in_loop: the clip frame that frame index `frame` (any integer, before 0 or past the end) shows when
// a clip of `frames` frames plays as a loop: frame -1 is the last frame, frame `frames` the first.
//   inputs:  frame (any int), frames (> 0)
//   output:  frame mod frames, in [0, frames)
// The measures that look at a window of frames around each one take looping clips' windows around the
// loop with it (metrics/free_limb_deviation.hpp, core/joint_flips.hpp).

namespace crowdlab {

inline int frame_in_loop(int frame, int frames) {
  const int r = frame % frames;
  return r < 0 ? r + frames : r;
}

}  // namespace crowdlab
