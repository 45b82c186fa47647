#pragma once
// The recipes of the stages that present a condition (stimuli/presentation_stages.hpp), issue 30: plain
// structs holding exactly what render_clip and write_contact_sheet (render_clip.hpp) read, built from the
// spec's render section in one place (presentation_recipes()). Their canonical bytes are the stages'
// input hashes (framework/pipeline/stage.hpp), so a change of the look (background, fog, overlap mode,
// MSAA, characters, viewpoint overrides, image size) redoes both clips and contact sheets, a change of
// the encoding (crf) only the clips, and a change outside (the protocol's text) neither.
//   StimulusLook        what an image of the crowd looks like (both stages)
//   RenderRecipe        render: clip.mp4 and clip.json of one condition (the look, viewpoint, encoding)
//   ContactSheetRecipe  contact_sheet: <method>.contact_sheet.png of a crowd group (the look; V1-V4 at
//                       the middle frame)
//   StimulusCheckRecipe stimulus_check (`run --check-only`): stimulus_check.json of one condition, the
//                       render stage's check without its clip (the look, viewpoint, overlap sampling)
// The character files' contents are the stages' input files, not recipe values.
#include <string>
#include <string_view>
#include <vector>

#include "framework/spec/experiment_spec.hpp"
#include "stimuli/render_clip.hpp"

namespace crowdlab::stimuli {

struct StimulusLook {
  int width = 1920, height = 1080;  ///< pixels
  SceneOptions scene;               ///< overlap mode, background, fog, MSAA, shadow map size
  ViewpointOverrides viewpoint_overrides;
  std::vector<std::string> character_files;  ///< skinned glTF characters (resolved paths)
};

struct RenderRecipe {
  static constexpr std::string_view kStage = "render";
  /// Bump when the framing rule (viewpoint.hpp, crowd_extent.hpp), the clip's making or the stimulus
  /// check in its sidecar (stimulus_check.hpp) changes. 2: cameras follow a travelling crowd, the stimulus
  /// check, dressed bodies and the clean image (issue 28). look/3: faces and hands weighted in the level-of-
  /// detail simplifier (issue 28, session 10). check/2: the check's overlap visibility (and overlap mode)
  /// from the rendered meshes' inside test, not the capsules (issue 27, session 11). look/4: smooth lip
  /// outlines, fewer grey heads (issue 28, session 12). shared-extent/3: the overhead view of a travelling
  /// crowd turns to frame it along the image's long side (viewpoint.cpp; issue 28, session 24). check/3:
  /// the inside test confirms its sign by a ray (metrics/surfaces_inside.hpp; issue 27, session 25). look/5:
  /// FXAA's edge test from the pixel's four neighbours, point-sampled (shaders.cpp; issue 28, session 26).
  /// look/6: FXAA on the CPU after the read (fxaa_rgba.hpp; issue 28, session 28).
  static constexpr std::string_view kCodeVersion = "shared-extent/3+check/3+look/6";
  StimulusLook look;
  ViewpointId viewpoint = ViewpointId::V1;  ///< the catalogue id (framework/core/viewpoint_catalogue.hpp)
  int crf = 18;
  std::string x264_preset = RenderOptions{}.x264_preset;
  bool frames_png = false;  ///< also write the frames as PNG (render.frames_png)
  /// The stimulus check draws every Nth frame again in overlap mode (render.check.overlap_every_frames;
  /// 0: not measured). Its thresholds only judge the result, so they are not part of the recipe.
  int check_overlap_every_frames = 10;
};

struct ContactSheetRecipe {
  static constexpr std::string_view kStage = "contact_sheet";
  /// look/3, look/4, look/5, shared-extent/3: as RenderRecipe; overlap/2: overlap mode from the rendered
  /// meshes (issue 27, session 11); overlap/3: their inside test confirmed by a ray (session 25).
  static constexpr std::string_view kCodeVersion = "shared-extent/3+look/5+overlap/3";
  StimulusLook look;
};

struct StimulusCheckRecipe {
  static constexpr std::string_view kStage = "stimulus_check";
  /// The render stage's: its framing, check and look make these numbers too, so one bump redoes both.
  static constexpr std::string_view kCodeVersion = RenderRecipe::kCodeVersion;
  StimulusLook look;
  ViewpointId viewpoint = ViewpointId::V1;
  int check_overlap_every_frames = 10;  ///< as RenderRecipe's
};

/// The look of the spec's stimuli. Throws InputError for a malformed render.background.
StimulusLook stimulus_look(const RenderSpec& render);
/// The render recipe of a condition shown from `viewpoint`.
RenderRecipe render_recipe(const ExperimentSpec& spec, ViewpointId viewpoint);
/// The check-only recipe of a condition shown from `viewpoint`: render_recipe's look, viewpoint and
/// overlap sampling, without the encoding.
StimulusCheckRecipe stimulus_check_recipe(const ExperimentSpec& spec, ViewpointId viewpoint);
/// The options render_clip and write_contact_sheet take for `look` (the encoding at its defaults).
RenderOptions render_options(const StimulusLook& look);

}  // namespace crowdlab::stimuli
