#include "experiments/cli/pipeline/render_stages.hpp"

#include <memory>
#include <optional>

#include "experiments/cli/pipeline/library_versions.hpp"
#include "framework/core/sha256.hpp"
#include "stimuli/clip_sidecar.hpp"
#include "stimuli/crowd_extent.hpp"
#include "stimuli/render_clip.hpp"
#include "stimuli/renderer.hpp"

namespace crowdlab::cli {
namespace fs = std::filesystem;
using nlohmann::json;
using stimuli::parse_hex_colour;
using stimuli::render_clip;
using stimuli::Renderer;
using stimuli::RenderOptions;
using stimuli::write_contact_sheet;

namespace {

/// Version of the framing rule; part of the render hashes, so clips framed by an older rule re-render.
constexpr const char* kFramingRule = "shared-extent/1";

class RenderStages final : public PresentationStages {
 public:
  explicit RenderStages(const ExperimentSpec& spec) : spec_(spec) {}

  void run(StageRunner& runner, CrowdGroup& g, const Condition& c, const fs::path& out_dir,
           const fs::path& condition_dir, StimulusEntry& e) override {
    const CrowdMethod method = c.params.method;
    RenderOptions ro = render_options();
    // render.frames_png: the rendered frames themselves, before H.264 (tests hash their pixels).
    if (spec_.render.frames_png) ro.frames_png_dir = (condition_dir / "frames").string();
    const fs::path clip = condition_dir / "clip.mp4";
    runner.run(render_stage(g, method, c.params.viewpoint, ro, clip));
    if (spec_.outputs.contact_sheet) runner.run(contact_sheet_stage(g, method, ro));
    e.file = fs::relative(clip, out_dir).string();
    e.width = ro.width;
    e.height = ro.height;
    e.sha256 = sha256_file_hex(clip.string());
  }

 private:
  /// The camera depends on the shared framing data (trajectories and heights: the baseline's file
  /// covers both), the framing rule, the viewpoint, the image size and the overrides (in the spec).
  Stage render_stage(CrowdGroup& g, CrowdMethod method, const std::string& viewpoint, const RenderOptions& ro,
                     const fs::path& clip) {
    auto view = std::make_shared<std::optional<stimuli::Viewpoint>>();
    const CrowdAnimation& crowd = g.animation(method);
    Stage s;
    s.name = "render";
    s.params = json{{"viewpoint", viewpoint},
                    {"width", ro.width},
                    {"height", ro.height},
                    {"crf", ro.crf},
                    {"msaa", ro.scene.msaa_samples},
                    {"overlap", ro.scene.overlap},
                    {"characters", ro.character_files},
                    {"framing", kFramingRule},
                    {"spec", spec_.source_hash}};
    s.inputs = {g.animation_path(method), g.animation_path(CrowdMethod::baseline)};
    s.compute = [this, &g, view, viewpoint, ro] {
      view->emplace(viewpoint, extent(g), ro.width, ro.height, ro.viewpoint_overrides);
    };
    s.outputs.push_back({clip, [this, &crowd, view, ro](const fs::path& tmp) {
                           render_clip(renderer(), crowd, ro, **view, tmp.string());
                         }});
    s.outputs.push_back({stimuli::clip_sidecar_path(clip), [&crowd, view](const fs::path& tmp) {
                           write_text_file(
                               tmp, stimuli::clip_sidecar(**view, crowd.frame_count(), crowd).dump(2) + "\n");
                         }});
    return s;
  }

  Stage contact_sheet_stage(CrowdGroup& g, CrowdMethod method, const RenderOptions& ro) {
    const CrowdAnimation& crowd = g.animation(method);
    Stage s;
    s.name = "contact_sheet";
    s.params = json{{"w", ro.width}, {"h", ro.height}, {"framing", kFramingRule}};
    s.inputs = {g.animation_path(method), g.animation_path(CrowdMethod::baseline)};
    s.outputs.push_back({g.dir() / (std::string(kind_name(method)) + ".contact_sheet.png"),
                         [this, &g, &crowd, ro](const fs::path& tmp) {
                           write_contact_sheet(renderer(), crowd, ro, crowd.frame_count() / 2, tmp.string(),
                                               &extent(g));
                         }});
    return s;
  }

  /// What every clip of the group is framed by: the crowd stage's trajectories (3D surface frames for
  /// manifold crowds) and the body heights of the animation stage, which the correction stage keeps.
  const stimuli::CrowdExtent& extent(CrowdGroup& g) {
    if (extent_ && extent_key_ == g.dir()) return *extent_;
    const std::vector<double> heights = stimuli::body_heights_m(g.animation(CrowdMethod::baseline));
    const ScenarioResult& s = g.scenario();
    const SurfaceTrajectories& surface = g.surface();
    extent_ = stimuli::crowd_extent(surface.empty() ? stimuli::character_tracks(s.trajectories, heights)
                                                    : stimuli::character_tracks(surface, heights),
                                    s.trajectories.fps);
    extent_key_ = g.dir();
    return *extent_;
  }

  Renderer& renderer() {
    if (!renderer_) renderer_ = std::make_unique<Renderer>();
    return *renderer_;
  }

  RenderOptions render_options() const {
    RenderOptions r;
    r.width = spec_.render.width;
    r.height = spec_.render.height;
    r.crf = spec_.render.crf;
    r.scene.overlap = spec_.render.overlap;
    r.scene.msaa_samples = spec_.render.msaa;
    r.scene.background = parse_hex_colour(spec_.render.background, "render.background");
    r.scene.fog_density = spec_.render.fog ? 0.02 : 0.0;
    r.viewpoint_overrides = spec_.render.viewpoint_overrides;
    r.character_files = spec_.render.characters;
    return r;
  }

  const ExperimentSpec& spec_;
  std::unique_ptr<Renderer> renderer_;
  fs::path extent_key_;
  std::optional<stimuli::CrowdExtent> extent_;
};

}  // namespace

RunSummary run_with_stimuli(const ExperimentSpec& spec, const RunOptions& options) {
  RunOptions with_versions = options;
  with_versions.libraries = library_versions();
  RenderStages render(spec);
  return run_experiment(spec, with_versions, &render);
}

}  // namespace crowdlab::cli
