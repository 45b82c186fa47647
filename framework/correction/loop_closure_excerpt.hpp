#pragma once
// The frames of a looping clip that its loop closure's per-character choice reads (issue 28, session 17).
//
// Every closure candidate changes only the clip's first frames (the next lap's start, the cuts from the
// next lap: [0, 2W) at most) or its last W (the blends, the arm closures), W the closing window. Each
// candidate is a copy of the whole crowd, so on a 20 s clip (600 frames, W = 60) the choice held 42
// copies of 600 frames where 180 differ (60 characters: ~1.2 GB). An excerpt keeps frames [0, head) and
// [tail_begin, N) only, with a margin of W_flip unchanged frames on each side of the join between them
// (flip_window(fps).frames): a joint flip at frame f compares f with its W_flip predecessors
// (core/joint_flips.hpp), so a
// flip counted across the join is counted alike on a candidate and on the unclosed clip, and "adds no
// flips" decides as on the whole clip. Depths between unchanged frames are the unclosed clip's, within the
// choice's limit, so dropping them decides nothing either (loop_closure_choice.hpp).
#include <cstddef>

#include "framework/core/crowd_animation.hpp"
#include "framework/correction/loop_closure_choice.hpp"

namespace crowdlab {

/// Frames [0, head) and [tail_begin, frames) of a clip of `frames` frames; head == tail_begin == frames
/// is the whole clip.
struct ClosureExcerpt {
  int frames = 0, head = 0, tail_begin = 0;

  /// The excerpt keeping the first head_frames and the last tail_frames frames of a clip of `frames`,
  /// each with `margin` unchanged frames more; the whole clip where those would meet.
  static ClosureExcerpt of(int frames, int head_frames, int tail_frames, int margin);

  /// Frames the excerpt keeps.
  int size() const { return head + frames - tail_begin; }
  /// Index in the excerpt of kept clip frame f.
  int index(int f) const { return f < head ? f : head + f - tail_begin; }
  /// A span of kept clip frames (all in the head or all in the tail) in excerpt indices.
  FrameSpan map(FrameSpan s) const { return {index(s.begin), index(s.end - 1) + 1}; }
  /// The clip's kept frames, every character (shapes, names, environment and metadata the clip's).
  CrowdAnimation cut(const CrowdAnimation& clip) const;
  /// Writes a character's excerpt frames back to their places in the clip's character.
  void put_back(const CharacterAnimation& excerpt, CharacterAnimation& clip) const;
};

}  // namespace crowdlab
