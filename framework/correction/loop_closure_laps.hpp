#pragma once
// The laps a looping clip's correction steps after its recorded one (issue 28; used by correct_crowd.cpp).
//
// NextLap (session 17): the corrector's next lap after the clip's own end, stepped only as far as the loop
// closure reads it (the next lap's start, the joints cut from it; correct_crowd.cpp close_loop).
//
// An extra recorded lap (session 19): where the closure leaves characters open, the next lap is stepped
// whole and recorded in the clip's place (then the clip's own end is its lead lap's end), closed again,
// and kept when its seam is smaller and its contacts no deeper (keep_extra_lap). Why: the laps of a dense
// crowd are chaotic, and which characters end a lap apart changes from lap to lap; session 18 measured a
// fifth lead lap for every clip (docs/stimuli.md, "Session 18: seed 1's D5 seam"): the seed-1 D5 concert's
// seam 1.85 -> 1.35x, but seed 2's 1.20 -> 1.54x and every looping output changed (+17 % steps). Recorded
// only where the closure leaves characters open, clips that close on the first lap are unchanged.
#include <optional>
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "framework/core/progress.hpp"
#include "framework/correction/corrector.hpp"

namespace crowdlab {

/// The targets of frame f: every character's input pose.
void frame_targets(const CrowdAnimation& crowd, int f, std::vector<Pose>& targets);

/// A lap stepped whole and recorded as the clip (NextLap::record).
struct RecordedLap {
  CrowdAnimation clip;                     ///< the input with the lap's corrected poses
  std::optional<Corrector> before_window;  ///< the corrector before the lap's frame N - W (the closure runs
                                           ///< on from it); none when the lap was stepped without a window
  Corrector after;             ///< the corrector after the lap's last frame (its next lap starts from it)
  int rejected_steps = 0;      ///< steps of the lap (and of the next lap's start read before) that failed
  int unconverged_steps = 0;   ///< the lap's steps where CG stopped above its tolerance
  double contacts_mean = 0.0;  ///< the lap's mean contacts per step
  double cg_iterations_mean = 0.0;
};

/// The corrector's next lap after the clip's own end, stepped only as far as it is read (session 17). Why:
/// session 16 ran a whole lap after every looping clip (+9 % corrector steps at 4 s, +18 % at 20 s), where
/// only the per-character choice reads it, and at most its first 2W frames (the start: W; the cuts: up to
/// kCutSpanWindows W).
class NextLap {
 public:
  /// after_clip: the corrector at the clip's last frame; window: the closure's W; progress (optional)
  /// advanced once per step.
  NextLap(Corrector after_clip, const CrowdAnimation& input, int window, Progress* progress);

  /// The lap's first `frames` poses per character (poses[c][f]: frame f of the lap after the clip).
  std::vector<std::vector<Pose>> first(int frames);
  /// Frames stepped so far.
  int stepped() const { return static_cast<int>(poses_.front().size()); }
  /// Steps whose solve failed (state kept), so far.
  int rejected_steps() const { return rejected_; }
  /// The whole lap, stepped to its end, as a recorded clip (session 19; the lap is spent). correct_crowd
  /// records its clip this way too, from the last lead lap's end.
  RecordedLap record() &&;

 private:
  Corrector corrector_;
  std::optional<Corrector> before_window_;  ///< taken when the lap passes frame N - W - 1
  const CrowdAnimation* input_;
  int window_;
  Progress* progress_;
  int rejected_ = 0, unconverged_ = 0;
  double contacts_ = 0.0, iterations_ = 0.0;
  std::vector<std::vector<Pose>> poses_;
};

/// The loop seam of a clip in the world: the mean distance (m) of every joint of every character from the
/// clip's last frame to its first, over the median over f of the same mean from frame f to f + 1. The
/// stimulus check's seam_step_ratio (stimuli/stimulus_check.hpp) is this ratio on screen, per camera.
/// 0 for a clip of fewer than three frames or without motion.
double world_seam_step_ratio(const CrowdAnimation& clip);

/// What decides between two recorded laps, each closed (correct_crowd.cpp).
struct ClosedLap {
  double seam_step_ratio = 0.0;  ///< world_seam_step_ratio of the closed clip
  double deepest_m = 0.0;        ///< its deepest inter-body penetration over all frames
  int open_characters = 0;       ///< characters its closure left open
};

/// Whether `extra` (the next lap recorded and closed) replaces `kept` (the lap kept so far): a smaller seam,
/// and its deepest contact no deeper than kept's, or than depth_floor_m (the depth a closure may always
/// reach) where kept's is shallower.
bool keep_extra_lap(const ClosedLap& kept, const ClosedLap& extra, double depth_floor_m);

}  // namespace crowdlab
