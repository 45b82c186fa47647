#pragma once
// Corrector: the online interface of the collision-correction solver (seed 000 §3), usable one frame
// at a time inside a game or VR loop:
//
//   Corrector corrector(shapes, params, env, fps);
//   every frame: std::vector<Pose> corrected = corrector.step(animation_poses_this_frame);
//
// Inputs: one BodyShape per character (fixed for the corrector's life), the static environment, the
// frame rate (the step is h = 1/fps, or 1/(n fps) in n substeps when 1/fps is longer than
// params.max_step_s, the targets interpolated between frames). step() takes one target Pose per character
// (the uncorrected animation at this frame) and returns the corrected poses in the same order. The first step
// returns its targets (the state starts at rest on them). Throws InputError for bad shapes, params, fps, an
// empty crowd, a wrong number of poses or a NaN/Inf/non-unit pose.
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "framework/correction/corrector_model.hpp"
#include "framework/correction/corrector_state.hpp"

namespace crowdlab {

class Corrector {
 public:
  explicit Corrector(std::vector<BodyShape> shapes, CorrectorParams params = {}, Environment env = {},
                     double fps = 30);

  /// Advances one frame of 1/fps (model().substeps steps) and returns the corrected poses.
  std::vector<Pose> step(const std::vector<Pose>& targets);

  const CorrectorModel& model() const { return model_; }
  const CorrectorState& state() const { return state_; }
  /// Foot holds on (default) or off. Off releases every held foot; when turned back on, feet the
  /// input plants are held from where they are then. correct_crowd() turns them off while it settles.
  void set_foot_holds(bool on) { state_.foot_holds_enabled = on; }

  /// Statistics of the last step (contacts, CG iterations, convergence, rejection).
  const StepStats& last_stats() const { return state_.stats; }

 private:
  CorrectorModel model_;
  CorrectorState state_;
};

}  // namespace crowdlab
