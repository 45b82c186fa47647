#pragma once
// `crowdlab run`'s presentation stages (framework/pipeline/run_experiment.hpp: PresentationStages),
// composed here because framework/ must not depend on stimuli/:
//   stage          output (DIR/conditions/<id>/ or DIR/crowds/<key>/)   input hash covers
//   render         clip.mp4 and its sidecar clip.json (with the clip's   viewpoint, image size, crf, msaa,
//                  stimulus check)                                       overlap, characters, framing rule,
//                                                                        check version and overlap sample
//                                                                        step, spec text; the animation shown
//                                                                        and the baseline (framing)
//   contact_sheet  <method>.contact_sheet.png (outputs.contact_sheet)    image size, framing rule; same
// Both methods of a condition are framed by the crowd group's shared extent (the crowd stage's
// trajectories and the animation stage's body heights), so `baseline` and `ours` get the same camera.
#include "framework/pipeline/run_experiment.hpp"

namespace crowdlab::cli {

/// run_experiment() with the renderer's stages and every library's version in the sidecars. Every clip
/// gets the stimulus check (stimuli/stimulus_check.hpp) in its sidecar and manifest row; a clip outside
/// the spec's render.check is logged as a warning, and with `strict` the run then throws RuntimeError
/// (after writing everything, manifest included).
RunSummary run_with_stimuli(const ExperimentSpec& spec, const RunOptions& options, bool strict = false);

}  // namespace crowdlab::cli
