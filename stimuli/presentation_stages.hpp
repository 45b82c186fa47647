#pragma once
// The stimuli module's stages of `crowdlab run`, contributed as data to the framework's run pipeline
// (framework/pipeline/run_experiment.hpp: PresentationStage), in the order they run per condition:
//   stage          output                                              recipe; inputs
//   render         DIR/conditions/<id>/clip.mp4 and its sidecar       RenderRecipe; the animation shown,
//                  clip.json (the condition's stimulus, with its        baseline.glb and trajectories.csv
//                  stimulus check, also in the manifest entry)         (framing), the character files
//   contact_sheet  DIR/crowds/<key>/<method>.contact_sheet.png        ContactSheetRecipe; the same
//                  (only with outputs.contact_sheet)
// Neither runs without outputs.video. `run --check-only` runs, instead of both, (check_only_stages):
//   stimulus_check DIR/conditions/<id>/stimulus_check.json: the       StimulusCheckRecipe; as render's
//                  render stage's check and camera, no clip
// Both methods of a condition are framed by the crowd group's shared extent (the crowd stage's
// trajectories and the animation stage's body heights), so `baseline` and `ours` get the same camera.
// One Renderer (an EGL context and its mesh cache) serves every stage of the run.
#include <string>
#include <vector>

#include "framework/pipeline/run_experiment.hpp"

namespace crowdlab::stimuli {

/// The render and contact-sheet stages of `spec`'s run. Throws InputError for a malformed
/// render.background. Every clip's stimulus check (stimulus_check.hpp) goes into its sidecar and manifest
/// entry; a clip outside the spec's render.check is logged as a warning and, when `check_failures` is
/// given, appended to it as "<condition id>: <reason>" (`run --strict` fails on any; it must outlive the
/// run).
std::vector<PresentationStage> presentation_stages(const ExperimentSpec& spec,
                                                   std::vector<std::string>* check_failures = nullptr);

/// `run --check-only`'s one stage: every condition's stimulus check, the same numbers the render stage
/// writes into clip.json (the geometry from the crowd and camera, the overlap measures from the frames
/// the render stage draws again in overlap mode), without drawing or encoding the clip; whatever
/// outputs.video says. Failures as presentation_stages().
std::vector<PresentationStage> check_only_stages(const ExperimentSpec& spec,
                                                 std::vector<std::string>* check_failures = nullptr);

}  // namespace crowdlab::stimuli
