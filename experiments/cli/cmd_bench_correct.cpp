// `crowdlab bench correct`: median ms per step of the collision-correction solver (seed 000 §3) on a
// stationary swaying crowd (framework/correction/swaying_crowd_fixture.hpp) at a given density.
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "experiments/cli/bench_group.hpp"
#include "experiments/cli/command_registry.hpp"
#include "framework/core/error.hpp"
#include "framework/correction/corrector.hpp"
#include "framework/correction/swaying_crowd_fixture.hpp"
#include "framework/metrics/correction_quality.hpp"
#include "framework/metrics/measure_crowd.hpp"

namespace crowdlab::cli {
namespace {

/// Peak resident set size of this process (MB), from /proc/self/status VmHWM.
double peak_rss_mb() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return 0.0;
}

/// CPU time of the whole process (all threads), ms: on a shared machine the wall time of a step
/// includes time spent waiting for a core, the CPU time does not.
double process_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

double median_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

struct Options {
  int characters = 60;
  double density = 6.66;
  int steps = 100;
  int warmup = 10;
  int threads = 0;
  bool json = false;
  double stiffness = CorrectorParams{}.stiffness;
  double damping = CorrectorParams{}.damping;
  double contact_stiffness = CorrectorParams{}.contact_stiffness;
  double cg_tolerance = CorrectorParams{}.cg_tolerance;
  int active_set_passes = CorrectorParams{}.active_set_passes;
  bool quality = false;
  bool inertial_prediction = false;
};

void run(const Options& o) {
  if (o.characters < 1) throw InputError("--characters must be >= 1");
  if (o.steps < 1) throw InputError("--steps must be >= 1");
  if (o.warmup < 0) throw InputError("--warmup must be >= 0");
  if (o.threads < 0) throw InputError("--threads must be >= 0");
  const int threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));

  SwayingCrowdOptions fixture;
  fixture.characters = o.characters;
  fixture.density_per_m2 = o.density;
  fixture.frames = o.warmup + o.steps;
  const CrowdAnimation crowd = make_swaying_crowd_fixture(fixture);
  std::vector<BodyShape> shapes;
  for (const auto& ch : crowd.characters) shapes.push_back(ch.shape);
  CorrectorParams params;
  params.stiffness = o.stiffness;
  params.damping = o.damping;
  params.contact_stiffness = o.contact_stiffness;
  params.cg_tolerance = o.cg_tolerance;
  params.active_set_passes = o.active_set_passes;
  params.exact_prediction = !o.inertial_prediction;
  Corrector corrector(std::move(shapes), params, crowd.environment, crowd.meta.fps);

  std::vector<Pose> targets(crowd.characters.size());
  std::vector<double> ms, cpu_ms;
  double contacts = 0.0, inter = 0.0, iterations = 0.0, pairs = 0.0, pulling = 0.0, passes = 0.0;
  int rejected = 0, unconverged = 0;
  CrowdAnimation corrected = crowd;  // written only with --quality (outside the timed region)
  for (int f = 0; f < fixture.frames; ++f) {
    for (size_t c = 0; c < targets.size(); ++c)
      targets[c] = crowd.characters[c].frames[static_cast<size_t>(f)];
    const double c0 = process_cpu_ms();
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<Pose>& out = corrector.step(targets);
    const auto t1 = std::chrono::steady_clock::now();
    const double c1 = process_cpu_ms();
    if (o.quality)
      for (size_t c = 0; c < targets.size(); ++c)
        corrected.characters[c].frames[static_cast<size_t>(f)] = out[c];
    if (f < o.warmup) continue;
    ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    cpu_ms.push_back(c1 - c0);
    const StepStats& st = corrector.last_stats();
    contacts += st.contacts();
    inter += st.inter_body_contacts;
    iterations += st.cg_iterations;
    pairs += st.body_pairs;
    pulling += st.pulling_contacts;
    passes += st.active_set_passes;
    rejected += st.rejected ? 1 : 0;
    unconverged += st.converged ? 0 : 1;
  }
  const double median = median_of(ms), cpu_median = median_of(cpu_ms);
  double mean = 0.0;
  for (double v : ms) mean += v;
  mean /= static_cast<double>(ms.size());
  const double n = static_cast<double>(ms.size());
  const double rss = peak_rss_mb();
  // Quality of the timed steps (the warm-up settles the input's own initial interpenetration).
  CorrectionQuality quality;
  double overlap_in = 0.0, overlap_out = 0.0;
  if (o.quality) {
    quality = measure_correction_quality(crowd, corrected, o.warmup);
    MetricsOptions mo;
    mo.pair_volumes = false;
    CrowdAnimation in_part = crowd, out_part = corrected;
    for (auto* a : {&in_part, &out_part})
      for (auto& ch : a->characters) ch.frames.erase(ch.frames.begin(), ch.frames.begin() + o.warmup);
    overlap_in = measure_crowd(in_part, mo).mean_character_overlap_l;
    overlap_out = measure_crowd(out_part, mo).mean_character_overlap_l;
  }
  if (o.json) {
    nlohmann::json j;
    j["ms_per_step_median"] = median;
    j["ms_per_step_mean"] = mean;
    j["cpu_ms_per_step_median"] = cpu_median;
    j["pulling_contacts_mean"] = pulling / n;
    j["active_set_passes_mean"] = passes / n;
    j["characters"] = o.characters;
    j["density_per_m2"] = o.density;
    j["steps"] = o.steps;
    j["contacts_mean"] = contacts / n;
    j["inter_body_contacts_mean"] = inter / n;
    j["body_pairs_mean"] = pairs / n;
    j["cg_iterations_mean"] = iterations / n;
    j["rejected_steps"] = rejected;
    j["unconverged_steps"] = unconverged;
    j["peak_rss_mb"] = rss;
    j["peak_rss_mb_per_character"] = rss / o.characters;
    j["threads"] = threads;
    if (o.quality) {
      j["overlap_baseline_l"] = overlap_in;
      j["overlap_corrected_l"] = overlap_out;
      j["overlap_reduction"] = overlap_in > 0 ? 1.0 - overlap_out / overlap_in : 0.0;
      j["depth_p99_m"] = quality.depth_p99_m;
      j["depth_max_m"] = quality.depth_max_m;
      j["rotation_dev_mean_deg"] = quality.rotation_dev_mean_deg;
      j["rotation_dev_p99_deg"] = quality.rotation_dev_p99_deg;
      j["foot_skate_max_m"] = quality.foot_skate_max_m;
      j["joint_speed_max_mps"] = quality.joint_speed_max_mps;
    }
    std::printf("%s\n", j.dump().c_str());
  } else {
    std::printf("bench correct: %d characters at %.2f /m^2, %d steps (+%d warm-up), %d thread(s)\n",
                o.characters, o.density, o.steps, o.warmup, threads);
    std::printf("  ms/step   median %.3f  mean %.3f  (CPU time, all threads: median %.3f)\n", median, mean,
                cpu_median);
    std::printf("  contacts  mean %.1f (inter-body %.1f), body pairs %.1f\n", contacts / n, inter / n,
                pairs / n);
    std::printf("  CG        mean %.2f iterations; %d unconverged, %d rejected steps\n", iterations / n,
                unconverged, rejected);
    std::printf("  active set: mean %.2f pulling contacts removed, %.2f extra passes per step\n", pulling / n,
                passes / n);
    if (o.quality)
      std::printf(
          "  quality   overlap %.4f -> %.4f L per character (-%.1f %%), depth p99 %.1f mm max %.1f mm,\n"
          "            rotation deviation mean %.2f deg p99 %.2f deg, foot skate %.1f mm, max joint speed "
          "%.1f m/s\n",
          overlap_in, overlap_out, overlap_in > 0 ? 100 * (1 - overlap_out / overlap_in) : 0.0,
          1000 * quality.depth_p99_m, 1000 * quality.depth_max_m, quality.rotation_dev_mean_deg,
          quality.rotation_dev_p99_deg, 1000 * quality.foot_skate_max_m, quality.joint_speed_max_mps);
    std::printf("  memory    peak RSS %.1f MB (%.3f MB per character, fixture animation included)\n", rss,
                rss / o.characters);
  }
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto opts = std::make_shared<Options>();
  auto* cmd = bench_group(root)->add_subcommand(
      "correct", "Collision-correction solver: median ms per step on a stationary swaying crowd");
  cmd->add_option("--characters", opts->characters, "Number of characters")->capture_default_str();
  cmd->add_option("--density", opts->density, "Characters per square metre")->capture_default_str();
  cmd->add_option("--steps", opts->steps, "Timed steps")->capture_default_str();
  cmd->add_option("--warmup", opts->warmup, "Untimed steps first")->capture_default_str();
  cmd->add_option("--threads", opts->threads, "TBB threads (0 = all cores)")->capture_default_str();
  cmd->add_option("--stiffness", opts->stiffness, "Control spring k (Eq. 4, per unit inertia, 1/s^2)")
      ->capture_default_str();
  cmd->add_option("--damping", opts->damping, "Control damping d (Eq. 4)")->capture_default_str();
  cmd->add_option("--contact-stiffness", opts->contact_stiffness, "Collision penalty k_delta (N/m)")
      ->capture_default_str();
  cmd->add_option("--cg-tolerance", opts->cg_tolerance, "CG relative residual tolerance")
      ->capture_default_str();
  cmd->add_option("--active-set-passes", opts->active_set_passes,
                  "Re-solves per step after removing pulling contacts (0 = off)")
      ->capture_default_str();
  cmd->add_flag("--inertial-prediction", opts->inertial_prediction,
                "Detect contacts at the inertial prediction instead of the exact contact-free step");
  cmd->add_flag("--quality", opts->quality,
                "Also measure the correction quality of the timed steps (overlap, depth, deviation, skate)");
  cmd->add_flag("--json", opts->json, "Print one JSON object");
  cmd->callback([opts] { run(*opts); });
});

}  // namespace
}  // namespace crowdlab::cli
