#pragma once
// `crowdlab run`'s presentation stages (framework/pipeline/run_experiment.hpp: PresentationStages),
// composed here because framework/ must not depend on stimuli/:
//   stage          output (DIR/conditions/<id>/ or DIR/crowds/<key>/)   input hash covers
//   render         clip.mp4 and its sidecar clip.json                    viewpoint, image size, crf, msaa,
//                                                                        overlap, characters, framing rule,
//                                                                        spec text; the animation shown
//                                                                        and the baseline (framing)
//   contact_sheet  <method>.contact_sheet.png (outputs.contact_sheet)    image size, framing rule; same
// Both methods of a condition are framed by the crowd group's shared extent (the crowd stage's
// trajectories and the animation stage's body heights), so `baseline` and `ours` get the same camera.
#include "framework/pipeline/run_experiment.hpp"

namespace crowdlab::cli {

/// run_experiment() with the renderer's stages and every library's version in the sidecars.
RunSummary run_with_stimuli(const ExperimentSpec& spec, const RunOptions& options);

}  // namespace crowdlab::cli
