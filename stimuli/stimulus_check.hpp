#pragma once
// The stimulus check (issue 28 item 7): does a rendered clip show what the study needs? `crowdlab run`
// computes it for every clip and writes it into the clip's sidecar ("stimulus_check") and manifest.csv
// (framework/core/stimulus_manifest.hpp: StimulusCheck, -1 = not measured).
//
// The geometric measures come from the crowd and the camera of every frame (no pixels, no occlusion):
// a character's body points are its 24 joints and the top of its head (the head bone's point at
// height_m above the floor in the rest pose).
//   crowd_in_frame_min      per frame, the share of characters whose body points all project inside
//                           the image and lie in front of the camera; the minimum over the clip.
//   character_height_px     per frame and character in the image, the vertical extent (px) of its
//                           projected body points: head to feet for an upright body seen from the side,
//                           foreshortened from above; the median over frames and characters.
//   seam_step_ratio         step(N-1 -> 0) / median over f of step(f -> f+1), where step(a -> b) is the
//                           mean on-screen displacement (px) of every body point of every character from
//                           frame a seen by camera a to frame b seen by camera b (points behind either
//                           camera are left out). When the camera moves, the same ratio of the still
//                           world (ground points around the camera's target) counts too, whichever is
//                           larger: a following camera that jumps back at the loop shows there. A clip
//                           whose motion is periodic over its length scores about 1; a crowd that jumps
//                           back when the clip restarts scores far above.
// The overlap measures come from overlap mode (renderer.hpp: SceneOptions::overlap, seed 000 Fig. 5):
//   overlap_frame_share     share of the sampled frames with at least one overlap pixel;
//   overlap_pixel_fraction  mean over those frames of the share of the image's pixels showing overlap.
//
// Thresholds: the spec's render.check (framework/spec/experiment_spec.hpp: StimulusCheckSpec).
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "framework/core/stimulus_manifest.hpp"
#include "framework/spec/experiment_spec.hpp"
#include "stimuli/viewpoint.hpp"

namespace crowdlab::stimuli {

/// The geometric measures (crowd in frame, character height, seam) of the first `frames` frames of
/// `crowd` seen from `view`; the overlap fields stay -1. Throws InputError when frames < 1 or exceeds
/// the crowd's frame count.
StimulusCheck measure_stimulus_geometry(const CrowdAnimation& crowd, const Viewpoint& view, int frames);

/// Fills the overlap fields of `check` from overlap-pixel fractions of sampled frames (each in [0, 1]).
void add_overlap_measures(StimulusCheck& check, const std::vector<double>& overlap_fractions);

/// What a clip is, for judging its check: its viewpoint, whether it shows the uncorrected baseline,
/// whether it is shown looping, and its image height (pixel thresholds scale with height / 1080).
struct ClipRole {
  std::optional<ViewpointId> viewpoint;  ///< none: a clip without a catalogue viewpoint
  bool baseline = false;
  bool loops = true;
  int image_height = 1080;
};

/// One line per threshold the clip misses ("crowd in frame 0.81 < 0.95", ...); empty when it passes.
/// Unmeasured values (-1) are not judged.
std::vector<std::string> stimulus_check_failures(const StimulusCheck& check, const StimulusCheckSpec& limits,
                                                 const ClipRole& role);

/// The sidecar's "stimulus_check" object, and back (missing keys read as -1).
nlohmann::json stimulus_check_json(const StimulusCheck& check);
StimulusCheck stimulus_check_from_json(const nlohmann::json& j);

}  // namespace crowdlab::stimuli
