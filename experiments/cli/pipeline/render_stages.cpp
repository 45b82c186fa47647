#include "experiments/cli/pipeline/render_stages.hpp"

#include <fstream>
#include <memory>
#include <optional>

#include <spdlog/spdlog.h>
#include "experiments/cli/pipeline/library_versions.hpp"

#include "framework/core/error.hpp"
#include "framework/core/sha256.hpp"
#include "stimuli/clip_sidecar.hpp"
#include "stimuli/crowd_extent.hpp"
#include "stimuli/overlap_samples.hpp"
#include "stimuli/render_clip.hpp"
#include "stimuli/renderer.hpp"
#include "stimuli/stimulus_check.hpp"

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
constexpr const char* kFramingRule = "shared-extent/2";
/// Version of the stimulus check written into the sidecar (stimuli/stimulus_check.hpp).
constexpr const char* kStimulusCheck = "stimulus-check/1";

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

class RenderStages final : public PresentationStages {
 public:
  explicit RenderStages(const ExperimentSpec& spec) : spec_(spec) {}

  /// "<condition id>: <reason>" for every clip outside the spec's render.check thresholds.
  const std::vector<std::string>& check_failures() const { return check_failures_; }

  void run(StageRunner& runner, CrowdGroup& g, const Condition& c, const fs::path& out_dir,
           const fs::path& condition_dir, StimulusEntry& e) override {
    const CrowdMethod method = c.params.method;
    RenderOptions ro = render_options();
    // render.frames_png: the rendered frames themselves, before H.264 (tests hash their pixels).
    if (spec_.render.frames_png) ro.frames_png_dir = (condition_dir / "frames").string();
    const fs::path clip = condition_dir / "clip.mp4";
    auto check = std::make_shared<StimulusCheck>();
    runner.run(render_stage(g, method, c.params.viewpoint, ro, clip, check));
    judge(c, *check, ro);
    e.check = *check;
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
                     const fs::path& clip, const std::shared_ptr<StimulusCheck>& check) {
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
                    {"check", kStimulusCheck},
                    {"check_overlap_every", spec_.render.check.overlap_every_frames},
                    {"spec", spec_.source_hash}};
    s.inputs = {g.animation_path(method), g.animation_path(CrowdMethod::baseline)};
    s.compute = [this, &g, view, viewpoint, ro] {
      view->emplace(viewpoint, extent(g), ro.width, ro.height, ro.viewpoint_overrides);
    };
    // The clip's own overlap pixels (render.overlap), handed to the sidecar's stimulus check.
    auto clip_overlap = std::make_shared<std::optional<std::vector<double>>>();
    s.outputs.push_back({clip, [this, &crowd, view, ro, clip_overlap](const fs::path& tmp) {
                           const stimuli::RenderResult r =
                               render_clip(renderer(), crowd, ro, **view, tmp.string());
                           if (ro.scene.overlap) *clip_overlap = r.red_fraction;
                         }});
    // Written after the clip, or alone when only it was lost (then the overlap frames are drawn again).
    s.outputs.push_back(
        {stimuli::clip_sidecar_path(clip), [this, &crowd, view, ro, clip_overlap](const fs::path& tmp) {
           nlohmann::json j = stimuli::clip_sidecar(**view, crowd.frame_count(), crowd);
           j["stimulus_check"] =
               stimuli::stimulus_check_json(measure_check(crowd, ro, **view, *clip_overlap));
           write_text_file(tmp, j.dump(2) + "\n");
         }});
    // Up to date or just written: the check is what the sidecar holds.
    s.load = [clip, check] {
      const nlohmann::json j = read_sidecar_json(stimuli::clip_sidecar_path(clip));
      *check = stimuli::stimulus_check_from_json(j.value("stimulus_check", nlohmann::json::object()));
    };
    return s;
  }

  /// The stimulus check of a clip: geometry from the crowd and camera path, overlap from the clip's own
  /// overlap pixels when it was rendered in overlap mode, else from every Nth frame drawn in overlap mode.
  StimulusCheck measure_check(const CrowdAnimation& crowd, const RenderOptions& ro,
                              const stimuli::Viewpoint& view,
                              const std::optional<std::vector<double>>& clip_overlap) {
    const int frames = crowd.frame_count();
    StimulusCheck check = stimuli::measure_stimulus_geometry(crowd, view, frames);
    const int every = ro.scene.overlap ? 1 : spec_.render.check.overlap_every_frames;
    if (clip_overlap)
      stimuli::add_overlap_measures(check, *clip_overlap);
    else if (every > 0)
      stimuli::add_overlap_measures(
          check, stimuli::sample_overlap_fractions(renderer(), crowd, ro, view, frames, every));
    return check;
  }

  /// Warns about (and records, for --strict) a clip outside the spec's render.check thresholds.
  void judge(const Condition& c, const StimulusCheck& check, const RenderOptions& ro) {
    const stimuli::ClipRole role{c.params.viewpoint, c.params.method == CrowdMethod::baseline,
                                 spec_.protocol.loop_video, ro.height};
    for (const std::string& why : stimuli::stimulus_check_failures(check, spec_.render.check, role)) {
      spdlog::warn("{}: stimulus check: {}", c.id, why);
      check_failures_.push_back(c.id + ": " + why);
    }
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
  std::vector<std::string> check_failures_;
  std::unique_ptr<Renderer> renderer_;
  fs::path extent_key_;
  std::optional<stimuli::CrowdExtent> extent_;
};

}  // namespace

RunSummary run_with_stimuli(const ExperimentSpec& spec, const RunOptions& options, bool strict) {
  RunOptions with_versions = options;
  with_versions.libraries = library_versions();
  RenderStages render(spec);
  const RunSummary summary = run_experiment(spec, with_versions, &render);
  const std::vector<std::string>& failed = render.check_failures();
  if (strict && !failed.empty()) {
    std::string list;
    for (const std::string& f : failed) list += "\n  " + f;
    throw RuntimeError(
        "run --strict: " + std::to_string(failed.size()) +
        " stimulus check(s) outside render.check (the run's outputs and manifest are written):" + list);
  }
  return summary;
}

}  // namespace crowdlab::cli
