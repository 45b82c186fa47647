// `crowdlab bench render`: frames per second of the stimulus renderer, render plus H.264 encode, and where
// a frame's time goes. With no options it measures a real stimulus of the seed 000 study: the stationary
// concert crowd at D5 (60 dancing characters with the spec's body model) from V3 at 1920x1080
// (bench_render_scene.hpp); `--scene synthetic` measures the procedural test crowd
// (stimuli/synthetic_crowd.hpp) instead.
#include <sys/resource.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numeric>
#include <vector>

#include "experiments/cli/bench_group.hpp"
#include "experiments/cli/bench_render_scene.hpp"
#include "experiments/cli/command_table.hpp"
#include "framework/core/error.hpp"
#include "stimuli/render_clip.hpp"
#include "stimuli/render_quality.hpp"
#include "stimuli/synthetic_crowd.hpp"

namespace crowdlab::cli::cmd_bench_render {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}
/// CPU time of this process (all threads, including llvmpipe's and x264's), seconds.
double load_average() {
  double l[1] = {0.0};
  return getloadavg(l, 1) == 1 ? l[0] : -1.0;
}
double process_cpu_s() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}
double mean(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

struct Args {
  std::string scene = "paper", spec, condition, body_model;
  double density = 6.66;
  int characters = 60, width = 1920, height = 1080, frames = 60, warmup = 5, crf = 18;
  double spacing = 0.55;
  std::string viewpoint = "V3", preset = "veryfast", out, frames_png;
  int msaa = 1, shadow_map = 2048;
  double lod_pixels = 6.0;
  bool overlap = false, json = false, empty = false, stages = false, quality = false, raw = false;
};

CrowdAnimation make_crowd(const Args& a) {
  if (a.scene == "synthetic") {
    stimuli::SyntheticCrowdOptions co;
    co.characters = a.characters;
    co.frames = a.frames + a.warmup;
    co.spacing_m = a.spacing;
    return stimuli::make_synthetic_crowd(co);
  }
  BenchRenderScene scene;
  scene.spec_path = a.spec;
  scene.condition_id = a.condition;
  scene.density = a.density;
  if (!a.body_model.empty()) scene.body_model = parse_kind<BodyModel>(a.body_model);
  CrowdAnimation crowd = make_bench_render_crowd(scene);
  const size_t wanted = static_cast<size_t>(a.frames + a.warmup);
  for (CharacterAnimation& c : crowd.characters)  // only the frames the bench draws
    if (c.frames.size() > wanted) c.frames.resize(wanted);
  return crowd;
}

/// Median over the timed frames of one stage.
template <typename Get>
double stage_median(const stimuli::RenderResult& r, std::ptrdiff_t skip, Get get) {
  std::vector<double> v;
  for (size_t f = static_cast<size_t>(skip); f < r.passes.size(); ++f) v.push_back(get(f));
  return median(v);
}

/// Fast path against the reference (render_quality.hpp) on frames 0, 10, 20 and 29 of V1..V4.
nlohmann::json quality_json(stimuli::Renderer& renderer, const CrowdAnimation& crowd,
                            const stimuli::RenderOptions& fast) {
  const int frames = std::min(30, crowd.frame_count());
  std::vector<int> samples;
  for (int f : {0, 10, 20, 29})
    if (f < frames) samples.push_back(f);
  const stimuli::QualityReport q =
      stimuli::measure_render_quality(renderer, crowd, fast, stimuli::reference_render_options(fast),
                                      {ViewpointId::V1, ViewpointId::V2, ViewpointId::V3, ViewpointId::V4},
                                      frames, samples, std::filesystem::temp_directory_path().string());
  nlohmann::json j = {{"ssim_min", q.ssim_min},
                      {"ssim_median", q.ssim_median},
                      {"psnr_min_db", q.psnr_min_db},
                      {"reference", "4x MSAA, shadow-mapped ground every frame, raw pixels (no encoding)"}};
  for (const stimuli::QualitySample& s : q.samples)
    j["samples"].push_back(
        {{"viewpoint", s.viewpoint}, {"frame", s.frame}, {"ssim", s.ssim}, {"psnr_db", s.psnr_db}});
  return j;
}

void run(const Args& a) {
  if (a.frames < 1 || a.warmup < 0) throw InputError("bench render: --frames must be >= 1 and --warmup >= 0");
  const std::optional<ViewpointId> viewpoint = find_viewpoint(a.viewpoint);
  if (!viewpoint) throw InputError("bench render: --viewpoint: unknown viewpoint '" + a.viewpoint + "'");
  const CrowdAnimation crowd = make_crowd(a);
  stimuli::RenderOptions ro;
  ro.width = a.width;
  ro.height = a.height;
  ro.crf = a.crf;
  ro.x264_preset = a.preset;
  ro.scene.overlap = a.overlap;
  ro.scene.msaa_samples = a.msaa;
  ro.scene.shadow_map_size = a.shadow_map;
  ro.scene.characters = !a.empty;
  ro.scene.lod_pixels = a.lod_pixels;
  ro.scene.clean_image = !a.raw;
  ro.frames_png_dir = a.frames_png;
  const std::string out =
      a.out.empty() ? (std::filesystem::temp_directory_path() / "crowdlab_bench_render.mp4").string() : a.out;
  stimuli::Renderer renderer;
  const auto setup_start = std::chrono::steady_clock::now();
  renderer.load_crowd(crowd);  // builds the meshes now, so render_clip finds them cached
  const double mesh_setup_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - setup_start).count();
  const double cpu_start = process_cpu_s();
  const stimuli::RenderResult r = stimuli::render_clip(renderer, crowd, ro, *viewpoint, out);
  const double cpu_ms_per_frame = 1000.0 * (process_cpu_s() - cpu_start) / std::max(1, r.frames);
  // The stage breakdown comes from a second pass over the same frames with every GPU pass finished before
  // the next starts (so it can be timed); the fps and CPU figures above come from the normal pipeline.
  stimuli::RenderOptions staged = ro;
  staged.scene.time_passes = true;
  const stimuli::RenderResult r_stages =
      a.json || a.stages ? stimuli::render_clip(renderer, crowd, staged, *viewpoint, out) : r;
  if (a.out.empty()) std::filesystem::remove(out);
  const nlohmann::json quality = a.quality ? quality_json(renderer, crowd, ro) : nlohmann::json();
  const auto skip = static_cast<std::ptrdiff_t>(std::min(a.warmup, r.frames - 1));
  const std::vector<double> render(r.render_ms.begin() + skip, r.render_ms.end());
  const std::vector<double> encode(r.encode_ms.begin() + skip, r.encode_ms.end());
  std::vector<double> interval;
  for (size_t f = static_cast<size_t>(skip) + 1; f < r.done_ms.size(); ++f)
    interval.push_back(r.done_ms[f] - r.done_ms[f - 1]);
  const double interval_median = median(interval);
  const double fps_median = interval_median > 0 ? 1000.0 / interval_median : 0.0;
  const double measured_s =
      r.done_ms.back() / 1000.0 - (skip > 0 ? r.done_ms[static_cast<size_t>(skip) - 1] / 1000.0 : 0.0);
  const double fps_mean = measured_s > 0 ? static_cast<double>(r.frames - skip) / measured_s : 0.0;
  if (a.json) {
    nlohmann::json j = {
        {"fps_median", fps_median},
        {"fps_mean", fps_mean},
        {"render_ms_median", median(render)},
        {"render_ms_mean", mean(render)},
        {"encode_ms_median", median(encode)},
        {"encode_ms_mean", mean(encode)},
        {"frames", r.frames - skip},
        {"warmup_frames", skip},
        {"characters", a.characters},
        {"triangles_per_frame", renderer.triangles_per_frame()},
        {"width", a.width},
        {"height", a.height},
        {"overlap", a.overlap},
        {"empty", a.empty},
        {"msaa", a.msaa},
        {"clean_image", !a.raw},
        {"shadow_map", a.shadow_map},
        {"lod_pixels", a.lod_pixels},
        {"x264_preset", a.preset},
        {"mesh_setup_s", mesh_setup_s},
        {"cpu_ms_per_frame", cpu_ms_per_frame},
        {"scene", a.scene == "synthetic" ? "synthetic" : crowd.meta.condition_id},
        {"quality", quality},
        {"stages_ms_median",
         {{"prepare", stage_median(r_stages, skip, [&](size_t f) { return r_stages.passes[f].prepare_ms; })},
          {"shadow", stage_median(r_stages, skip, [&](size_t f) { return r_stages.passes[f].shadow_ms; })},
          {"colour", stage_median(r_stages, skip, [&](size_t f) { return r_stages.passes[f].colour_ms; })},
          {"resolve", stage_median(r_stages, skip, [&](size_t f) { return r_stages.passes[f].resolve_ms; })},
          {"readback", stage_median(r_stages, skip, [&](size_t f) { return r_stages.readback_ms[f]; })},
          {"fxaa", stage_median(r_stages, skip, [&](size_t f) { return r_stages.aa_ms[f]; })},
          {"convert", stage_median(r_stages, skip, [&](size_t f) { return r_stages.convert_ms[f]; })},
          {"encode", stage_median(r_stages, skip, [&](size_t f) { return r_stages.encode_ms[f]; })}}},
        {"load_average_1min", load_average()},
        {"device", r.device}};
    std::printf("%s\n", j.dump().c_str());
  } else {
    std::printf("render bench: %d characters, %dx%d, %d frames (+%d warm-up), viewpoint %s, overlap %s\n",
                a.characters, a.width, a.height, r.frames - static_cast<int>(skip), static_cast<int>(skip),
                a.viewpoint.c_str(), a.overlap ? "on" : "off");
    std::printf("device: %s\n", r.device.c_str());
    std::printf("mesh setup: %.2f s, %zu triangles per frame (characters)\n", r.setup_s,
                renderer.triangles_per_frame());
    std::printf("end to end: %.2f fps median, %.2f fps mean\n", fps_median, fps_mean);
    std::printf("render (skin + draw + resolve + readback): %.1f ms median, %.1f ms mean\n", median(render),
                mean(render));
    std::printf(
        "encode (yuv420p + x264 %s): %.1f ms median, %.1f ms mean (worker thread, overlaps rendering)\n",
        a.preset.c_str(), median(encode), mean(encode));
    const std::vector<double> aa(r.aa_ms.begin() + skip, r.aa_ms.end());
    if (median(aa) > 0.0)  // the clean image at one sample per pixel
      std::printf("clean image anti-aliasing (FXAA): %.1f ms median (worker thread, overlaps rendering)\n",
                  median(aa));
  }
}

}  // namespace

void add_bench_render_command(Command& root) {
  auto args = std::make_shared<Args>();
  auto* cmd = bench_group(root)->add_subcommand(
      "render", "Stimulus rendering + H.264 encoding throughput (frames per second)");
  cmd->add_option("--scene", args->scene,
                  "paper: a real seed 000 stimulus (stationary concert crowd, --density, the spec's body "
                  "model); synthetic: the procedural test crowd (--characters, --spacing)")
      ->capture_default_str()
      ->check(check::is_member({"paper", "synthetic"}));
  cmd->add_option("--spec", args->spec, "Paper scene: this spec instead of the embedded gomez2024_stationary")
      ->check(check::existing_file());
  cmd->add_option("--condition", args->condition, "Paper scene: this condition id (default: by --density)");
  cmd->add_option("--density", args->density, "Paper scene: the density level (characters per m^2)")
      ->capture_default_str();
  cmd->add_option("--body-model", args->body_model, "Paper scene: procedural | mpfb2 (default: the spec's)")
      ->check(check::is_member(kind_names<BodyModel>()));
  cmd->add_option("--characters", args->characters, "Characters in the procedural crowd")
      ->capture_default_str()
      ->check(check::range(1, 10000));
  cmd->add_option("--width", args->width, "Frame width (even)")->capture_default_str();
  cmd->add_option("--height", args->height, "Frame height (even)")->capture_default_str();
  cmd->add_option("--frames", args->frames, "Timed frames")->capture_default_str();
  cmd->add_option("--warmup", args->warmup, "Untimed frames rendered first")->capture_default_str();
  cmd->add_option("--spacing", args->spacing, "Grid pitch of the crowd (metres)")->capture_default_str();
  cmd->add_option("--viewpoint", args->viewpoint, "V1|V2|V3|V4|pair|tracking")->capture_default_str();
  cmd->add_option("--crf", args->crf, "x264 CRF")->capture_default_str();
  cmd->add_option("--preset", args->preset, "x264 preset")->capture_default_str();
  cmd->add_option("--out", args->out, "Keep the clip at this path (default: temporary, deleted)");
  cmd->add_flag("--raw", args->raw,
                "The raw draw: no FXAA, hard shadow edges, no contact darkening (to compare with the clean "
                "image, the default)");
  cmd->add_option("--frames-png", args->frames_png, "Also write every frame as DIR/frame_NNNNN.png (slower)");
  cmd->add_flag("--overlap", args->overlap, "Overlap mode (red pixels)");
  cmd->add_option(
         "--msaa", args->msaa,
         "MSAA samples (1: the stimuli's fast path, the default of render.msaa; 4: the quality reference)")
      ->capture_default_str()
      ->check(check::range(1, 16));
  cmd->add_option("--shadow-map", args->shadow_map, "Shadow map size (pixels)")
      ->capture_default_str()
      ->check(check::range(64, 8192));
  cmd->add_option("--lod-pixels", args->lod_pixels, "Level-of-detail screen-space error bound (pixels)")
      ->capture_default_str()
      ->check(check::range(0.0, 100.0));
  cmd->add_flag("--empty", args->empty,
                "Draw the scene without its characters: the fixed cost of a frame (clear, ground, resolve, "
                "readback, encode), i.e. the ceiling of this machine");
  cmd->add_flag("--json", args->json, "Print one JSON object, with each stage's median (implies --stages)");
  cmd->add_flag(
      "--quality", args->quality,
      "Also compare frames 0, 10, 20 and 29 of V1-V4, rendered and encoded with these options, with a "
      "reference (4x MSAA, no encoding): luma SSIM and PSNR");
  cmd->add_flag("--stages", args->stages,
                "Also render the frames once more with each GPU pass finished before the next, and print "
                "each stage's median time");
  cmd->callback([args] { run(*args); });
}

}  // namespace crowdlab::cli::cmd_bench_render
