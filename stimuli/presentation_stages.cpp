#include "stimuli/presentation_stages.hpp"

#include <spdlog/spdlog.h>

#include <fstream>
#include <memory>
#include <optional>

#include "framework/core/error.hpp"
#include "framework/core/write_file.hpp"
#include "stimuli/clip_sidecar.hpp"
#include "stimuli/crowd_extent.hpp"
#include "stimuli/overlap_samples.hpp"
#include "stimuli/presentation_recipes.hpp"
#include "stimuli/renderer.hpp"
#include "stimuli/stimulus_check.hpp"

namespace crowdlab::stimuli {
namespace fs = std::filesystem;

namespace {

/// What the stages of one run share: the renderer, and the framing extent of the current crowd group.
class PresentationContext {
 public:
  Renderer& renderer() {
    if (!renderer_) renderer_ = std::make_unique<Renderer>();
    return *renderer_;
  }

  /// What every clip of the group is framed by: the crowd stage's trajectories (3D surface frames for
  /// manifold crowds) and the body heights of the animation stage, which the correction stage keeps.
  const CrowdExtent& extent(CrowdGroup& g) {
    if (extent_ && extent_key_ == g.dir()) return *extent_;
    const std::vector<double> heights = body_heights_m(g.animation(CrowdMethod::baseline));
    const ScenarioResult& s = g.scenario();
    const SurfaceTrajectories& surface = g.surface();
    extent_ = crowd_extent(
        surface.empty() ? character_tracks(s.trajectories, heights) : character_tracks(surface, heights),
        s.trajectories.fps);
    extent_key_ = g.dir();
    return *extent_;
  }

 private:
  std::unique_ptr<Renderer> renderer_;
  fs::path extent_key_;
  std::optional<CrowdExtent> extent_;
};

/// The files a presentation stage of `method`'s crowd reads: the animation shown, what frames it (the
/// baseline's body heights and the crowd's trajectories) and the character files.
std::vector<fs::path> presentation_inputs(CrowdGroup& g, CrowdMethod method, const StimulusLook& look) {
  std::vector<fs::path> inputs{g.animation_path(method), g.animation_path(CrowdMethod::baseline)};
  for (const fs::path& p : g.crowd_paths()) inputs.push_back(p);
  for (const std::string& f : look.character_files) inputs.emplace_back(f);
  return inputs;
}

/// A clip's sidecar JSON; RuntimeError naming the file when it cannot be read or parsed.
nlohmann::json read_sidecar_json(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw RuntimeError(path.string() + ": cannot read the clip's sidecar");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw RuntimeError(path.string() + ": not valid JSON (" + e.what() + ")");
  }
}

/// The stimulus check of a clip (issue 28): geometry from the crowd and camera path, overlap from the
/// clip's own overlap pixels when it was rendered in overlap mode, else from every Nth frame drawn again
/// in overlap mode (N = 0: geometry only, and no renderer is made for it).
StimulusCheck measure_check(PresentationContext& ctx, const CrowdAnimation& crowd, const RenderOptions& ro,
                            const Viewpoint& view, const std::optional<std::vector<double>>& clip_overlap,
                            int overlap_every_frames) {
  const int frames = crowd.frame_count();
  StimulusCheck check = measure_stimulus_geometry(crowd, view, frames);
  const int every = ro.scene.overlap ? 1 : overlap_every_frames;
  if (clip_overlap)
    add_overlap_measures(check, *clip_overlap);
  else if (every > 0)
    add_overlap_measures(check, sample_overlap_fractions(ctx.renderer(), crowd, ro, view, frames, every));
  return check;
}

/// A clip's sidecar (its camera and characters, clip_sidecar.hpp) with its stimulus check, written to
/// `path`: the render stage's clip.json and the check-only stimulus_check.json.
void write_checked_sidecar(const fs::path& path, const Viewpoint& view, const CrowdAnimation& crowd,
                           const StimulusCheck& check) {
  nlohmann::json j = clip_sidecar(view, crowd.frame_count(), crowd);
  j["stimulus_check"] = stimulus_check_json(check);
  write_text_file(path, j.dump(2) + "\n");
}

Stage render_stage(const std::shared_ptr<PresentationContext>& ctx, const RenderRecipe& recipe, CrowdGroup& g,
                   CrowdMethod method, const fs::path& condition_dir) {
  const CrowdAnimation& crowd = g.animation(method);
  auto view = std::make_shared<std::optional<Viewpoint>>();
  RenderOptions ro = render_options(recipe.look);
  ro.crf = recipe.crf;
  ro.x264_preset = recipe.x264_preset;
  // render.frames_png: the rendered frames themselves, before H.264 (tests hash their pixels).
  if (recipe.frames_png) ro.frames_png_dir = (condition_dir / "frames").string();
  Stage s = stage_for(recipe);
  s.inputs = presentation_inputs(g, method, recipe.look);
  s.compute = [ctx, &g, view, recipe] {
    const StimulusLook& l = recipe.look;
    view->emplace(recipe.viewpoint, ctx->extent(g), l.width, l.height, l.viewpoint_overrides);
  };
  const fs::path clip = condition_dir / "clip.mp4";
  // The clip's own overlap pixels (render.overlap), handed to the sidecar's stimulus check.
  auto clip_overlap = std::make_shared<std::optional<std::vector<double>>>();
  s.outputs.push_back({clip, [ctx, &crowd, view, ro, clip_overlap](const fs::path& tmp) {
                         const RenderResult r = render_clip(ctx->renderer(), crowd, ro, **view, tmp.string());
                         if (ro.scene.overlap) *clip_overlap = r.red_fraction;
                       }});
  // Written after the clip, or alone when only it was lost (then the overlap frames are drawn again).
  const int every = recipe.check_overlap_every_frames;
  s.outputs.push_back(
      {clip_sidecar_path(clip), [ctx, &crowd, view, ro, clip_overlap, every](const fs::path& tmp) {
         write_checked_sidecar(tmp, **view, crowd,
                               measure_check(*ctx, crowd, ro, **view, *clip_overlap, every));
       }});
  return s;
}

/// `run --check-only`: the render stage's stimulus check of a condition without its clip, in
/// DIR/conditions/<id>/stimulus_check.json (the clip sidecar's camera and characters, and the check). The
/// numbers are the render stage's: the same geometry, and overlap from the same frames drawn in overlap
/// mode (every Nth; every frame when the clip itself would be drawn in overlap mode).
Stage check_stage(const std::shared_ptr<PresentationContext>& ctx, const StimulusCheckRecipe& recipe,
                  CrowdGroup& g, CrowdMethod method, const fs::path& condition_dir) {
  const CrowdAnimation& crowd = g.animation(method);
  Stage s = stage_for(recipe);
  s.inputs = presentation_inputs(g, method, recipe.look);
  const RenderOptions ro = render_options(recipe.look);
  const int every = recipe.check_overlap_every_frames;
  s.outputs.push_back(
      {condition_dir / "stimulus_check.json", [ctx, &g, &crowd, ro, recipe, every](const fs::path& tmp) {
         const StimulusLook& l = recipe.look;
         const Viewpoint view(recipe.viewpoint, ctx->extent(g), l.width, l.height, l.viewpoint_overrides);
         write_checked_sidecar(tmp, view, crowd, measure_check(*ctx, crowd, ro, view, std::nullopt, every));
       }});
  return s;
}

/// Fills a clip's stimulus check (from `sidecar`, up to date or just written: the clip's clip.json or
/// the check-only stimulus_check.json) into the manifest entry, and warns about (and records, for
/// --strict) a clip outside the spec's render.check.
void describe_clip(const ExperimentSpec& spec, std::vector<std::string>* failures, const Condition& c,
                   StimulusEntry& e, const fs::path& sidecar) {
  const nlohmann::json j = read_sidecar_json(sidecar);
  e.check = stimulus_check_from_json(j.value("stimulus_check", nlohmann::json::object()));
  const ClipRole role{c.params.viewpoint, c.params.method == CrowdMethod::baseline, spec.protocol.loop_video,
                      spec.render.height};
  for (const std::string& why : stimulus_check_failures(e.check, spec.render.check, role)) {
    spdlog::warn("{}: stimulus check: {}", c.id, why);
    if (failures) failures->push_back(c.id + ": " + why);
  }
}

Stage contact_sheet_stage(const std::shared_ptr<PresentationContext>& ctx, const ContactSheetRecipe& recipe,
                          CrowdGroup& g, CrowdMethod method) {
  const CrowdAnimation& crowd = g.animation(method);
  Stage s = stage_for(recipe);
  s.inputs = presentation_inputs(g, method, recipe.look);
  const RenderOptions ro = render_options(recipe.look);
  s.outputs.push_back({g.dir() / (std::string(kind_name(method)) + ".contact_sheet.png"),
                       [ctx, &g, &crowd, ro](const fs::path& tmp) {
                         write_contact_sheet(ctx->renderer(), crowd, ro, crowd.frame_count() / 2,
                                             tmp.string(), &ctx->extent(g));
                       }});
  return s;
}

}  // namespace

std::vector<PresentationStage> presentation_stages(const ExperimentSpec& spec,
                                                   std::vector<std::string>* check_failures) {
  auto ctx = std::make_shared<PresentationContext>();
  std::vector<PresentationStage> stages;
  const RenderRecipe clip = render_recipe(spec, ConditionParams{}.viewpoint);
  const bool video = spec.outputs.video;
  stages.push_back(
      {std::string(RenderRecipe::kStage),
       [ctx, clip, video](CrowdGroup& g, const Condition& c, const fs::path& dir) -> std::optional<Stage> {
         if (!video) return std::nullopt;
         RenderRecipe recipe = clip;
         recipe.viewpoint = c.params.viewpoint;
         return render_stage(ctx, recipe, g, c.params.method, dir);
       },
       true,
       [spec, check_failures](const Condition& c, const fs::path& dir, StimulusEntry& e) {
         describe_clip(spec, check_failures, c, e, clip_sidecar_path(dir / "clip.mp4"));
       }});
  ContactSheetRecipe sheet{stimulus_look(spec.render)};
  const bool sheets = video && spec.outputs.contact_sheet;
  stages.push_back(
      {std::string(ContactSheetRecipe::kStage),
       [ctx, sheet, sheets](CrowdGroup& g, const Condition& c, const fs::path&) -> std::optional<Stage> {
         if (!sheets) return std::nullopt;
         return contact_sheet_stage(ctx, sheet, g, c.params.method);
       },
       false,
       {}});
  return stages;
}

std::vector<PresentationStage> check_only_stages(const ExperimentSpec& spec,
                                                 std::vector<std::string>* check_failures) {
  auto ctx = std::make_shared<PresentationContext>();
  const StimulusCheckRecipe check = stimulus_check_recipe(spec, ConditionParams{}.viewpoint);
  return {{std::string(StimulusCheckRecipe::kStage),
           [ctx, check](CrowdGroup& g, const Condition& c, const fs::path& dir) -> std::optional<Stage> {
             StimulusCheckRecipe recipe = check;
             recipe.viewpoint = c.params.viewpoint;
             return check_stage(ctx, recipe, g, c.params.method, dir);
           },
           false,
           [spec, check_failures](const Condition& c, const fs::path& dir, StimulusEntry& e) {
             describe_clip(spec, check_failures, c, e, dir / "stimulus_check.json");
           }}};
}

}  // namespace crowdlab::stimuli
