// `crowdlab bench correct`: median ms per step of the collision-correction solver (seed 000 §3) on a
// stationary swaying crowd (framework/correction/swaying_crowd_fixture.hpp) at a given density.
// The measurement itself is run_correct_bench (bench_correct_run.hpp), shared with `reproduce gomez2024`.
#include <cstdio>
#include <memory>

#include "experiments/cli/bench_correct_run.hpp"
#include "experiments/cli/bench_group.hpp"
#include "experiments/cli/command_table.hpp"
#include "experiments/cli/corrector_tuning_options.hpp"

namespace crowdlab::cli::cmd_bench_correct {
namespace {

struct Options {
  CorrectBenchOptions bench;
  bool json = false;
};

void run(const Options& o) {
  const CorrectBenchResult r = run_correct_bench(o.bench);
  if (o.json) {
    std::printf("%s\n", correct_bench_json(r).dump().c_str());
    return;
  }
  std::printf("bench correct: %d characters at %.2f /m^2, %d steps (+%d warm-up), %d thread(s)\n",
              o.bench.characters, o.bench.density, o.bench.steps, o.bench.warmup, r.threads);
  std::printf("  ms/step   median %.3f  mean %.3f  (CPU time, all threads: median %.3f)\n", r.ms_median,
              r.ms_mean, r.cpu_ms_median);
  std::printf("  contacts  mean %.1f (inter-body %.1f), body pairs %.1f\n", r.contacts_mean,
              r.inter_body_contacts_mean, r.body_pairs_mean);
  std::printf("  CG        mean %.2f iterations; %d unconverged, %d rejected steps\n", r.cg_iterations_mean,
              r.unconverged_steps, r.rejected_steps);
  std::printf("  active set: mean %.2f pulling contacts removed, %.2f extra passes per step\n",
              r.pulling_contacts_mean, r.active_set_passes_mean);
  std::printf("  depenetration: mean %.1f capsule pairs deeper than the tolerance, %.2f passes per step\n",
              r.deep_contacts_mean, r.depenetration_passes_mean);
  if (o.bench.quality) {
    const CorrectionQuality& q = r.quality;
    const double in = r.overlap_baseline_l, out = r.overlap_corrected_l;
    std::printf(
        "  quality   overlap %.4f -> %.4f L per character (-%.1f %%), depth p99 %.1f mm max %.1f mm,\n"
        "            rotation deviation mean %.2f deg p99 %.2f deg, foot skate %.1f mm, max joint speed "
        "%.1f m/s\n",
        in, out, in > 0 ? 100 * (1 - out / in) : 0.0, 1000 * q.depth_p99_m, 1000 * q.depth_max_m,
        q.rotation_dev_mean_deg, q.rotation_dev_p99_deg, 1000 * q.foot_skate_max_m, q.joint_speed_max_mps);
  }
  std::printf("  memory    peak RSS %.1f MB (%.3f MB per character, fixture animation included)\n",
              r.peak_rss_mb, r.peak_rss_mb / o.bench.characters);
}

}  // namespace

void add_bench_correct_command(Command& root) {
  auto opts = std::make_shared<Options>();
  CorrectBenchOptions& b = opts->bench;
  auto* cmd = bench_group(root)->add_subcommand(
      "correct", "Collision-correction solver: median ms per step on a stationary swaying crowd");
  cmd->add_option("--characters", b.characters, "Number of characters")->capture_default_str();
  cmd->add_option("--density", b.density, "Characters per square metre")->capture_default_str();
  cmd->add_option("--steps", b.steps, "Timed steps")->capture_default_str();
  cmd->add_option("--warmup", b.warmup, "Untimed steps first")->capture_default_str();
  cmd->add_option("--threads", b.threads, "TBB threads (0 = all cores)")->capture_default_str();
  cmd->add_option("--stiffness", b.params.stiffness, "Control spring k (Eq. 4, per unit inertia, 1/s^2)")
      ->capture_default_str();
  cmd->add_option("--damping", b.params.damping, "Control damping d (Eq. 4)")->capture_default_str();
  add_corrector_tuning_options(cmd, b.params);
  cmd->add_flag_callback(
      "--inertial-prediction", [&b] { b.params.exact_prediction = false; },
      "Detect contacts at the inertial prediction instead of the exact contact-free step");
  cmd->add_flag("--quality", b.quality,
                "Also measure the correction quality of the timed steps (overlap, depth, deviation, skate)");
  cmd->add_flag("--json", opts->json, "Print one JSON object");
  cmd->callback([opts] { run(*opts); });
}

}  // namespace crowdlab::cli::cmd_bench_correct
