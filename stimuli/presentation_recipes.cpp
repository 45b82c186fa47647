#include "stimuli/presentation_recipes.hpp"

namespace crowdlab::stimuli {

StimulusLook stimulus_look(const RenderSpec& render) {
  StimulusLook look;
  look.width = render.width;
  look.height = render.height;
  look.scene.overlap = render.overlap;
  look.scene.msaa_samples = render.msaa;
  look.scene.background = parse_hex_colour(render.background, "render.background");
  look.scene.fog_density = render.fog ? 0.02 : 0.0;
  look.viewpoint_overrides = render.viewpoint_overrides;
  look.character_files = render.characters;
  return look;
}

RenderRecipe render_recipe(const ExperimentSpec& spec, ViewpointId viewpoint) {
  RenderRecipe r;
  r.look = stimulus_look(spec.render);
  r.viewpoint = viewpoint;
  r.crf = spec.render.crf;
  r.frames_png = spec.render.frames_png;
  r.check_overlap_every_frames = spec.render.check.overlap_every_frames;
  return r;
}

StimulusCheckRecipe stimulus_check_recipe(const ExperimentSpec& spec, ViewpointId viewpoint) {
  const RenderRecipe clip = render_recipe(spec, viewpoint);
  return {clip.look, clip.viewpoint, clip.check_overlap_every_frames};
}

RenderOptions render_options(const StimulusLook& look) {
  RenderOptions o;
  o.width = look.width;
  o.height = look.height;
  o.scene = look.scene;
  o.viewpoint_overrides = look.viewpoint_overrides;
  o.character_files = look.character_files;
  return o;
}

}  // namespace crowdlab::stimuli
