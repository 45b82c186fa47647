// `crowdlab render CROWD.glb --viewpoint V3 --out clip.mp4 [--overlap] ...`: one stimulus clip.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>

#include "experiments/cli/command_estimates.hpp"
#include "experiments/cli/command_table.hpp"
#include "framework/core/error.hpp"
#include "framework/core/write_file.hpp"
#include "framework/io/read_crowd_glb.hpp"
#include "framework/spec/estimate_work.hpp"
#include "framework/spec/work_limits.hpp"
#include "stimuli/clip_sidecar.hpp"
#include "stimuli/render_clip.hpp"
#include "stimuli/synthetic_crowd.hpp"

namespace crowdlab::cli::cmd_render {
namespace {

/// Frames of the `--synthetic` crowd.
constexpr int kSyntheticFrames = 90;

struct RenderArgs {
  std::string crowd_path, viewpoint = "V3", out, frames_png, contact_sheet, background = "#d8dde3",
                          preset = "veryfast";
  std::vector<std::string> overrides, characters;
  int width = 1920, height = 1080, crf = 18, synthetic = 0, max_frames = -1;
  double lod_pixels = stimuli::SceneOptions{}.lod_pixels;
  double fog = 0.0;
  bool overlap = false, synthetic_corridor = false;
};

/// "NAME=px,py,pz,tx,ty,tz,fov" -> placements[NAME], checked as the spec loader checks render.viewpoints.
void parse_override(const std::string& text, std::map<std::string, CameraPlacement>& placements) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--viewpoint-override: expected NAME=px,py,pz,tx,ty,tz,fov_deg, got \"" + text + "\"");
  std::vector<double> values;
  std::stringstream ss(text.substr(eq + 1));
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      size_t used = 0;
      values.push_back(std::stod(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw InputError("--viewpoint-override: \"" + item + "\" is not a number");
    }
  }
  const std::string name = text.substr(0, eq);
  if (values.size() != 7)
    throw InputError("--viewpoint-override " + name +
                     ": expected [px,py,pz,tx,ty,tz,fov_deg] (7 numbers), got " +
                     std::to_string(values.size()));
  CameraPlacement p{};
  std::copy(values.begin(), values.end(), p.begin());
  if (const std::string problem = camera_placement_problem(p); !problem.empty())
    throw InputError("--viewpoint-override " + name + ": " + problem);
  placements[name] = p;
}

/// --viewpoint: a placement given by --viewpoint-override, else a catalogue preset.
stimuli::Viewpoint chosen_viewpoint(const RenderArgs& a,
                                    const std::map<std::string, CameraPlacement>& placements,
                                    const CrowdAnimation& crowd, const stimuli::RenderOptions& o) {
  if (const auto p = placements.find(a.viewpoint); p != placements.end())
    return stimuli::Viewpoint::placed(a.viewpoint, p->second, o.width, o.height);
  if (const std::optional<ViewpointId> id = find_viewpoint(a.viewpoint))
    return stimuli::Viewpoint(*id, crowd, o.width, o.height, o.viewpoint_overrides);
  std::string known;
  for (const auto& n : viewpoint_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("--viewpoint: unknown viewpoint '" + a.viewpoint + "' (known: " + known +
                   ", or one named by --viewpoint-override)");
}

void run(const RenderArgs& a) {
  if (a.synthetic < 0)
    throw InputError(SourceLocation{"", 0, 0, "--synthetic"},
                     std::to_string(a.synthetic) + " characters; give 1 to " +
                         std::to_string(static_cast<int>(kMaxCharactersPerCrowd)));
  // The one crowd estimate (framework/spec/estimate_work.hpp), before the crowd is built.
  if (const auto problem =
          crowd_limit_problem("--synthetic " + std::to_string(a.synthetic), a.synthetic, kSyntheticFrames,
                              "give 1 to 10000 characters", "give fewer characters"))
    throw InputError(SourceLocation{"", 0, 0, "--synthetic"}, *problem);
  if (a.crowd_path.empty() == (a.synthetic == 0))
    throw InputError("render: give either a crowd file (CROWD.glb) or --synthetic N");
  // Before the crowd is built or rendered (issue 33); --max-frames cuts the clip.
  const auto announce_render = [&a](double characters, double frames) {
    announce_estimate(
        "render " + a.out,
        render_estimate(characters, a.max_frames >= 0 ? std::min<double>(frames, a.max_frames) : frames,
                        a.width, a.height));
  };
  CrowdAnimation crowd;
  if (a.synthetic > 0) {
    announce_render(a.synthetic, kSyntheticFrames);
    stimuli::SyntheticCrowdOptions co;
    co.characters = a.synthetic;
    co.frames = kSyntheticFrames;
    if (a.synthetic_corridor) {
      co.columns = 3;
      co.walk_speed_mps = 1.2;
      co.corridor_walls = true;
      co.stage = false;
    }
    crowd = stimuli::make_synthetic_crowd(co);
  } else {
    crowd = read_crowd_glb(a.crowd_path);
    announce_render(static_cast<double>(crowd.characters.size()), crowd.frame_count());
  }
  stimuli::RenderOptions o;
  o.width = a.width;
  o.height = a.height;
  o.crf = a.crf;
  o.x264_preset = a.preset;
  o.frames_png_dir = a.frames_png;
  o.max_frames = a.max_frames;
  o.scene.overlap = a.overlap;
  o.scene.background = stimuli::parse_hex_colour(a.background, "--background");
  if (!(a.fog >= 0.0)) throw InputError("--fog must be >= 0");
  o.scene.fog_density = a.fog;
  o.scene.lod_pixels = a.lod_pixels;
  std::map<std::string, CameraPlacement> placements;
  for (const std::string& text : a.overrides) parse_override(text, placements);
  for (const auto& [name, placement] : placements)  // catalogue names also place the contact sheet's views
    if (const std::optional<ViewpointId> id = find_viewpoint(name)) o.viewpoint_overrides[*id] = placement;
  o.character_files = a.characters;
  stimuli::Renderer renderer;
  // A lone crowd file is framed from its own motion (`crowdlab run` frames from the shared trajectories).
  const stimuli::Viewpoint view = chosen_viewpoint(a, placements, crowd, o);
  const std::filesystem::path sidecar = stimuli::clip_sidecar_path(a.out);
  if (sidecar == std::filesystem::path(a.out)) throw InputError("--out: the clip must not end in .json");
  // Via a temporary (write_file.hpp): a failed encode (a full disk) leaves no broken clip under --out.
  stimuli::RenderResult r;
  write_output_via_temporary(a.out, [&](const std::filesystem::path& tmp) {
    r = stimuli::render_clip(renderer, crowd, o, view, tmp.string());
  });
  write_file_atomic(sidecar, stimuli::clip_sidecar(view, r.frames, crowd).dump(2) + "\n");
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  spdlog::info("wrote {} and {}: {} frames, {:.2f} s at {} fps, {}x{} ({} characters)", a.out,
               sidecar.string(), r.frames, r.duration_s, r.fps, r.width, r.height, crowd.characters.size());
  spdlog::info(
      "render {:.1f} ms/frame, encode {:.1f} ms/frame (medians), {:.2f} s wall, mesh setup {:.2f} s on {}",
      median(r.render_ms), median(r.encode_ms), r.wall_s, r.setup_s, r.device);
  if (a.overlap) {
    const std::string csv = a.out + ".overlap.csv";
    std::ostringstream out;
    out << "frame,time_s,red_fraction\n";
    for (size_t f = 0; f < r.red_fraction.size(); ++f)
      out << f << ',' << f / r.fps << ',' << r.red_fraction[f] << '\n';
    write_file_atomic(csv, out.str());
    const double mean = std::accumulate(r.red_fraction.begin(), r.red_fraction.end(), 0.0) /
                        std::max<size_t>(1, r.red_fraction.size());
    spdlog::info("red-pixel fraction: mean {:.5f}, max {:.5f} (per frame in {})", mean,
                 *std::max_element(r.red_fraction.begin(), r.red_fraction.end()), csv);
  }
  if (!a.contact_sheet.empty()) {
    stimuli::write_contact_sheet(renderer, crowd, o, crowd.frame_count() / 2, a.contact_sheet);
    spdlog::info("wrote contact sheet {}", a.contact_sheet);
  }
}

}  // namespace

void add_render_command(Command& root) {
  auto a = std::make_shared<RenderArgs>();
  auto* cmd = root.add_subcommand(
      "render",
      "Render a crowd file to an H.264 MP4 stimulus (headless OpenGL: EGL surfaceless on CPU, or the GPU). "
      "Viewpoints: V1 front, V2 upper-front, V3 front-side, V4 overhead (seed 000), pair (seed 001's "
      "three-quarter view), tracking (follows character c000)");
  cmd->add_option("crowd", a->crowd_path, "Crowd file (.glb) written by crowdlab");
  cmd->add_option("--synthetic", a->synthetic,
                  "Render a procedural test crowd of N characters instead of a file");
  cmd->add_flag("--corridor", a->synthetic_corridor,
                "With --synthetic: a walking crowd between corridor walls");
  cmd->add_option("--viewpoint", a->viewpoint,
                  "V1|V2|V3|V4|pair|tracking, or a name given by --viewpoint-override")
      ->capture_default_str();
  cmd->add_option("-o,--out", a->out,
                  "Output MP4 file; its camera and characters go to a sidecar with the extension .json")
      ->required();
  cmd->add_flag("--overlap", a->overlap,
                "Paint pixels showing volume shared with another character red (seed 000 Fig. 5); writes "
                "OUT.overlap.csv with the red-pixel fraction per frame");
  cmd->add_option("--width", a->width, "Frame width in pixels (even)")->capture_default_str();
  cmd->add_option("--height", a->height, "Frame height in pixels (even)")->capture_default_str();
  cmd->add_option("--crf", a->crf, "x264 constant rate factor, 0 (lossless) to 51")->capture_default_str();
  cmd->add_option("--preset", a->preset, "x264 preset (ultrafast ... veryslow)")->capture_default_str();
  cmd->add_option("--frames-png", a->frames_png, "Also write every frame as DIR/frame_NNNNN.png");
  cmd->add_option("--max-frames", a->max_frames, "Render only the first N frames");
  cmd->add_option("--contact-sheet", a->contact_sheet, "Also write a 2x2 PNG of V1-V4 at the middle frame");
  cmd->add_option("--background", a->background, "Background colour #rrggbb")->capture_default_str();
  cmd->add_option("--fog", a->fog, "Exponential-squared fog density (1/m), 0 = off")->capture_default_str();
  cmd->add_option(
         "--character", a->characters,
         "Skinned glTF character (.glb/.gltf, e.g. Mixamo) drawn instead of the mannequin; repeatable, "
         "character i uses file i mod N")
      ->check(check::existing_file());
  cmd->add_option(
         "--lod-pixels", a->lod_pixels,
         "Level of detail: a character uses the coarsest mesh whose grid spans at most this many pixels")
      ->capture_default_str()
      ->check(check::range(0.0, 100.0));
  cmd->add_option("--viewpoint-override", a->overrides, "NAME=px,py,pz,tx,ty,tz,fov_deg (repeatable)");
  cmd->callback([a] { run(*a); });
}

}  // namespace crowdlab::cli::cmd_render
