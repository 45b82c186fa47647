// `crowdlab metrics CROWD.glb [--json]`: every interpenetration measure of a crowd animation on its
// capsule bodies (framework/metrics/measure_crowd.hpp): per-character mean overlap (seed 000 Fig. 3,
// litres), V (seed 001 Eq. 1), maximum penetration depth, collision events, per pair and per frame.
// With `--input BASE.glb` (the animation the crowd was corrected from) also the correction-quality
// measures (framework/metrics/correction_quality.hpp): inter-body depth p99 / max, joint deviation,
// stance-foot drift, foot pops, ground penetration and floating of the feet, free-limb deviation, joint
// flips and environment penetration (issue 27); for bodies with a rendered mesh, the mesh-level overlap
// and the proxy coverage (issue 27, sampled every 0.5 s).
#include <nlohmann/json.hpp>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "experiments/cli/command_estimates.hpp"
#include "experiments/cli/command_table.hpp"
#include "framework/core/error.hpp"
#include "framework/core/joint_flips.hpp"
#include "framework/core/progress.hpp"
#include "framework/core/skeleton.hpp"
#include "framework/core/surface_kind_name.hpp"
#include "framework/io/read_crowd_glb.hpp"
#include "framework/metrics/correction_quality.hpp"
#include "framework/metrics/measure_crowd.hpp"
#include "framework/pipeline/metrics_json.hpp"

namespace crowdlab::cli::cmd_metrics {
namespace {

struct MetricsArgs {
  std::string path;
  std::string input;  ///< the uncorrected animation, for the correction-quality measures
  bool json = false;
  bool per_frame = false;
  bool pair_volumes = true;
  bool mesh_measures = true;  ///< with --input: the mesh-level overlap and proxy coverage
  bool loop = false;          ///< with --input: the clip plays as a loop (the free-limb window wraps)
  int base_cells = OverlapOptions{}.base_cells;
  int depth = OverlapOptions{}.depth;
};

void print_text(const CrowdMetrics& m, const std::string& path, bool per_frame) {
  std::printf("%s: %d characters, %d frames at %g fps\n", path.c_str(), m.characters, m.frames, m.fps);
  std::printf("  mean per-character overlap (seed 000 Fig. 3): %.4f L\n", m.mean_character_overlap_l);
  std::printf("  V, mean cube root of overlap over colliding frames (seed 001 Eq. 1): %.4f m\n",
              m.volume_index_m);
  std::printf("  max penetration depth: %.4f m\n", m.max_penetration_depth_m);
  std::printf("  collision events: %d (frames with a collision: %d)\n", m.collision_count,
              m.colliding_frames);
  std::printf(
      "  largest rigorous error bound of one volume: %.4f L (a guaranteed bracket, far wider than the\n"
      "    actual error: see framework/metrics/overlap_volume.hpp)\n",
      1000.0 * m.max_error_bound_m3);
  if (!m.pairs.empty()) {
    std::printf("  colliding pairs (a b: frames events V_m max_volume_L max_depth_m):\n");
    for (const PairMetrics& p : m.pairs)
      std::printf("    %d %d: %d %d %.4f %.4f %.4f\n", p.a, p.b, p.colliding_frames, p.collision_events,
                  p.volume_index_m, 1000.0 * p.max_volume_m3, p.max_penetration_depth_m);
  }
  if (per_frame) {
    std::printf("  frame mean_character_overlap_L total_pair_overlap_L max_depth_m colliding_pairs\n");
    for (size_t f = 0; f < m.per_frame.size(); ++f) {
      const FrameMetrics& fm = m.per_frame[f];
      std::printf("    %zu %.5f %.5f %.4f %d\n", f, 1000.0 * fm.mean_character_overlap_m3,
                  1000.0 * fm.total_pair_overlap_m3, fm.max_penetration_depth_m, fm.colliding_pairs);
    }
  }
}

void print_quality(const CorrectionQuality& q, double fps) {
  const FootContactQuality& f = q.feet;
  std::printf(
      "  against the input: p99 / max inter-body depth %.1f / %.1f mm, mean / p99 joint deviation "
      "%.2f / %.2f deg\n",
      1000 * q.depth_p99_m, 1000 * q.depth_max_m, q.rotation_dev_mean_deg, q.rotation_dev_p99_deg);
  std::printf(
      "  stance-foot drift p99 / max %.1f / %.1f mm over %ld contact frames; foot pops %d (worst "
      "excess %.1f cm)\n",
      1000 * f.stance_drift_p99_m, 1000 * f.stance_drift_max_m, f.contact_frames, f.foot_pops,
      100 * f.pop_excess_max_m);
  std::printf(
      "  feet below the ground (y = 0): max %.1f mm (p99 %.1f); below min(0, the input's foot), added by the "
      "correction: max %.1f mm (p99 %.1f)\n",
      1000 * f.ground_penetration_max_m, 1000 * f.ground_penetration_p99_m,
      1000 * f.ground_penetration_added_max_m, 1000 * f.ground_penetration_added_p99_m);
  std::printf("  floating in stance: p99 %.1f mm (max %.1f)\n", 1000 * f.float_p99_m, 1000 * f.float_max_m);
  const FreeLimbDeviation& fl = q.free_limbs;
  std::printf(
      "  free-limb deviation (joints 10 cm from everyone for +-0.5 s): p99 / max %.2f / %.2f deg over %ld "
      "joint-frames",
      fl.p99_deg, fl.max_deg, fl.free_joint_frames);
  if (fl.worst_character >= 0)
    std::printf(" (max: character %d, %s, frame %d)", fl.worst_character,
                std::string(joint_name(fl.worst_joint)).c_str(), fl.worst_frame);
  const FlipWindow window = flip_window(fps);
  std::printf(
      "\n  joint flips (deviation change > %.1f deg within %d frame%s): %ld (largest change %.1f deg)\n",
      window.angle_deg, window.frames, window.frames == 1 ? "" : "s", q.flips.count, q.flips.max_change_deg);
  for (const JointFlip& j : q.flips.first)
    std::printf("    character %d, %s, frame %d: %.1f deg\n", j.character,
                std::string(joint_name(j.joint)).c_str(), j.frame, j.change_deg);
  const EnvironmentPenetration& e = q.environment;
  std::printf(
      "  environment penetration (capsules behind walls, barriers, stage): p99 / max %.1f / %.1f mm\n",
      1000 * e.p99_m, 1000 * e.max_m);
  const MeshOverlap& mo = q.mesh_overlap;
  if (mo.frames > 0) {
    std::printf(
        "  rendered meshes (%d frames, one every 0.5 s): vertices inside another character: mean / max "
        "%.4f / %.4f %%, depth p99 / max %.1f / %.1f mm",
        mo.frames, 100 * mo.fraction_mean, 100 * mo.fraction_max, 1000 * mo.depth_p99_m,
        1000 * mo.depth_max_m);
    if (mo.worst_character >= 0)
      std::printf(" (max: character %d in %d, frame %d)", mo.worst_character, mo.worst_other, mo.worst_frame);
    std::printf("\n");
  }
  const ProxyCoverage& pc = q.proxy_coverage;
  if (pc.frames > 0) {
    std::printf(
        "  proxy coverage: %.2f %% of rendered vertices within 5 mm of their own capsules; outside by p99 / "
        "max %.1f / %.1f mm\n   by surface:",
        100 * pc.within_share, 1000 * pc.outside_p99_m, 1000 * pc.outside_max_m);
    for (size_t k = 0; k < pc.within_share_by_surface.size(); ++k)
      if (pc.within_share_by_surface[k] >= 0)
        std::printf(" %s %.1f %%", surface_kind_name(static_cast<SurfaceKind>(k)),
                    100 * pc.within_share_by_surface[k]);
    std::printf("\n");
  }
}

void run(const MetricsArgs& args) {
  // Checked here, by option name, before the crowd is read (the quadrature refused them only at its
  // first pair, as "overlap_volume: options need ...").
  if (args.base_cells < 1 || args.base_cells > 4096)
    throw InputError(SourceLocation{"", 0, 0, "--base-cells"},
                     "must be 1 to 4096, got " + std::to_string(args.base_cells));
  if (args.depth < 0 || args.depth > 12)
    throw InputError(SourceLocation{"", 0, 0, "--depth"},
                     "must be 0 to 12, got " + std::to_string(args.depth));
  const CrowdAnimation crowd = read_crowd_glb(args.path);
  announce_estimate("metrics " + args.path,
                    metrics_estimate(static_cast<double>(crowd.characters.size()), crowd.frame_count(),
                                     args.base_cells, args.depth));
  MetricsOptions options;
  options.pair_volumes = args.pair_volumes;
  options.overlap.base_cells = args.base_cells;
  options.overlap.depth = args.depth;
  Progress progress("metrics " + args.path, static_cast<size_t>(std::max(1, crowd.frame_count())));
  options.on_frame_done = [&progress] { progress.advance(); };
  const CrowdMetrics m = measure_crowd(crowd, options);
  progress.finish();
  std::optional<CorrectionQuality> quality;
  if (!args.input.empty())
    quality =
        measure_correction_quality(read_crowd_glb(args.input), crowd, 0, 1, args.mesh_measures, args.loop);
  if (args.json) {
    nlohmann::json j = crowd_metrics_json(m, args.per_frame);
    if (quality) j["correction_quality"] = correction_quality_json(*quality);
    std::printf("%s\n", j.dump().c_str());
  } else {
    print_text(m, args.path, args.per_frame);
    if (quality) print_quality(*quality, crowd.meta.fps);
  }
}

}  // namespace

void add_metrics_command(Command& root) {
  auto args = std::make_shared<MetricsArgs>();
  auto* cmd = root.add_subcommand(
      "metrics",
      "Interpenetration measures of a crowd .glb on its capsule bodies: per-character mean overlap "
      "(litres), V (mean cube root of overlap volume), max penetration depth, collision events");
  cmd->add_option("crowd", args->path, "Crowd animation (.glb written by crowdlab)")
      ->required()
      ->check(check::existing_file());
  cmd->add_option(
         "--input", args->input,
         "The uncorrected animation CROWD was corrected from: adds depth p99, joint deviation, "
         "stance-foot drift, foot pops, ground penetration and floating of the feet, free-limb deviation, "
         "joint flips, environment penetration, and on rendered meshes (MPFB2 bodies, sampled every 0.5 s) "
         "the share of vertices inside another character's mesh and outside their own capsules")
      ->check(check::existing_file());
  cmd->add_flag("--json", args->json, "Print one JSON object");
  cmd->add_flag("--per-frame", args->per_frame, "Also print the per-frame series");
  cmd->add_flag("!--no-pair-volumes", args->pair_volumes,
                "Skip the per-pair volumes (V per pair and V of the clip become 0; faster)");
  cmd->add_flag("!--no-mesh-measures", args->mesh_measures,
                "With --input: skip the mesh-level measures (about three quarters of the time on MPFB2 "
                "bodies)");
  cmd->add_flag(
      "--loop", args->loop,
      "With --input: the clip plays as a loop (as `run` shows clips when protocol.loop_video is on): "
      "a joint is free only if nothing is near it within 0.5 s across the loop's seam too, and a jump at the "
      "seam counts as a flip");
  cmd->add_option("--base-cells", args->base_cells, "Overlap quadrature base grid cells")
      ->capture_default_str();
  cmd->add_option("--depth", args->depth, "Overlap quadrature subdivisions per base cell")
      ->capture_default_str();
  cmd->callback([args] { run(*args); });
}

}  // namespace crowdlab::cli::cmd_metrics
