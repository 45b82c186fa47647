// `crowdlab experiment overlap-vs-density --out DIR`: seed 000 Figure 3. For the stationary concert
// (20..60 characters on 9 m^2) and the corridor, the per-character mean overlap volume of the baseline
// animation and of the corrected one, at every density of the shipped specs.
// Writes DIR/overlap_vs_density.csv (scenario,characters,density,method,mean_overlap_l),
// DIR/overlap_vs_density_{stationary,corridor}.png|svg, and the correction-quality measures of the
// corrected animations (framework/metrics/correction_quality.hpp) in DIR/correction_quality.csv
// (scenario,characters,density,overlap_reduction,depth_p99_m,depth_max_m,rotation_dev_mean_deg,
// rotation_dev_p99_deg,foot_skate_max_m,joint_speed_max_mps,cg_iterations_mean,rejected_steps,
// stance_foot_drift_p99_m,stance_foot_drift_max_m,foot_pops,foot_pop_excess_max_m,
// foot_ground_penetration_max_m,foot_ground_penetration_added_max_m,foot_float_p99_m,free_limb_dev_p99_deg,
// free_limb_dev_max_deg,joint_flips,
// env_penetration_p99_m,env_penetration_max_m,mesh_overlap_fraction,baseline_mesh_overlap_fraction,
// mesh_overlap_depth_p99_m,proxy_coverage,proxy_outside_p99_m; the foot measures are defined in
// framework/metrics/foot_contact_quality.hpp, the next five (issue 27) in free_limb_deviation.hpp,
// joint_flips.hpp and environment_penetration.hpp, the last five (issue 27, rendered meshes; empty for
// bodies without one) in mesh_overlap.hpp and proxy_coverage.hpp). Both methods are measured with the
// capsules `run` gives the spec's scenario (animation.collision_proxies: fitted to the rendered meshes for
// the concert, volume-fitted for the corridor), or with --cover-mesh / --fit-proxies with capsules fitted
// to the rendered meshes in both (proxy_fit_options.hpp); with
// --save-crowds each density's crowds go to DIR/crowds/SCENARIO_density-D/{baseline,ours}.glb.
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>

#include "experiments/cli/command_table.hpp"
#include "experiments/cli/corrector_tuning_options.hpp"
#include "experiments/cli/experiment_group.hpp"
#include "experiments/cli/figures/overlap_vs_density.hpp"
#include "experiments/cli/pipeline/output_folder_lock.hpp"
#include "experiments/cli/proxy_fit_options.hpp"
#include "framework/animation/animate_crowd.hpp"
#include "framework/core/csv.hpp"
#include "framework/core/progress.hpp"
#include "framework/core/seed.hpp"
#include "framework/correction/correct_crowd.hpp"
#include "framework/crowd/generate_scenario.hpp"
#include "framework/io/write_crowd_glb.hpp"
#include "framework/metrics/correction_quality.hpp"
#include "framework/metrics/measure_crowd.hpp"
#include "framework/pipeline/body_model.hpp"
#include "framework/pipeline/crowd_recipes.hpp"
#include "framework/pipeline/provenance.hpp"
#include "framework/spec/load_experiment_spec.hpp"

namespace crowdlab::cli::cmd_experiment_overlap {
namespace {
namespace fs = std::filesystem;

struct Options {
  std::string out = "overlap-vs-density";
  std::string stationary = "experiments/gomez2024_stationary.yaml";
  std::string corridor = "experiments/gomez2024_nonstationary.yaml";
  double duration_s = 4.0;  ///< seconds of animation per density (the paper's clips are 20 s)
  double fps = 30.0;
  CorrectorParams params;  ///< solver parameters (the spec's damping overrides params.damping)
  bool inertial_prediction = false;
  /// The collision proxies both methods are measured with; empty: the spec's animation.collision_proxies
  /// for its scenario, as `run` fits them (pipeline/body_model.hpp).
  std::optional<ProxyFit> proxies;
  bool save_crowds = false;  ///< write each density's baseline.glb and ours.glb under out/crowds
};

struct QualityRow {
  std::string scenario;
  int characters = 0;
  double density = 0;
  double overlap_reduction = 0;  ///< 1 - ours / baseline mean overlap
  CorrectionQuality quality;
  CorrectionReport report;
  MeshOverlap baseline_mesh;  ///< the baseline's own mesh-level overlap (ours': quality.mesh_overlap)
};

/// Writes what one density measured, so that `crowdlab metrics`, `render` and `correct` can look again.
void save_crowds(const CrowdAnimation& baseline, const CrowdAnimation& ours, const fs::path& dir) {
  fs::create_directories(dir);
  write_crowd_glb(baseline, (dir / "baseline.glb").string());
  write_crowd_glb(ours, (dir / "ours.glb").string());
  spdlog::info("wrote {}/{{baseline,ours}}.glb", dir.string());
}

void run_scenario(const std::string& spec_path, const Options& o, std::vector<OverlapRow>& rows,
                  std::vector<QualityRow>& quality) {
  ExperimentSpec spec = load_experiment_spec(spec_path);
  spec.duration_s = o.duration_s;
  spec.fps = o.fps;
  std::set<std::string> done;
  for (const Condition& c : enumerate_conditions(spec)) {
    const std::string density = c.text("density", "");
    if (done.count(density)) continue;  // viewpoint and method do not change the crowd
    done.insert(density);
    Condition crowd_condition = c;
    crowd_condition.seed = derive_seed(spec.seed, "crowd/density-" + density);
    const ScenarioResult s = generate_scenario(spec, crowd_condition);
    const std::string scenario(kind_name(s.scenario));
    const double density_per_m2 = c.params.density_per_m2.value_or(0.0);
    AnimationContext ctx;
    ctx.scenario = s.scenario;
    ctx.seed = crowd_condition.seed;
    ctx.condition_id = "density-" + density;
    apply_body_model(spec.animation, s.trajectories.agents.size(), ctx);
    CrowdAnimation baseline = animate_crowd(s.trajectories, s.environment, spec.animation, ctx);
    // Before both are measured: one set of proxies for both.
    fit_crowd_proxies(baseline,
                      o.proxies.value_or(proxy_fit(resolve_collision_proxies(spec.animation, s.scenario))));
    CorrectorParams params = o.params;
    params.exact_prediction = !o.inertial_prediction;
    params.damping = spec.correction.damping;
    if (walks_on_flat_ground(s.scenario)) walking_correction(params);  // as `run` corrects it
    Progress progress(scenario + " density " + density + ": correcting", correction_steps(baseline, params));
    CorrectionReport report;
    const CrowdAnimation ours = correct_crowd(baseline, params, &progress, &report);
    progress.finish();
    if (o.save_crowds)
      save_crowds(baseline, ours, fs::path(o.out) / "crowds" / (scenario + "_density-" + density));
    const int n = static_cast<int>(baseline.characters.size());
    rows.push_back(
        {scenario, n, density_per_m2, "baseline", measure_crowd(baseline).mean_character_overlap_l});
    rows.push_back({scenario, n, density_per_m2, "ours", measure_crowd(ours).mean_character_overlap_l});
    std::printf("%-10s %3d characters (%.2f/m2): baseline %.3f L, ours %.3f L per character\n",
                scenario.c_str(), n, density_per_m2, rows[rows.size() - 2].mean_overlap_l,
                rows.back().mean_overlap_l);
    QualityRow qr{scenario,
                  n,
                  density_per_m2,
                  0.0,
                  measure_correction_quality(baseline, ours),
                  report,
                  measure_mesh_overlap(baseline)};
    const double base_l = rows[rows.size() - 2].mean_overlap_l;
    qr.overlap_reduction = base_l > 0.0 ? 1.0 - rows.back().mean_overlap_l / base_l : 0.0;
    std::printf(
        "%-10s %3d characters: overlap -%.1f %%, p99 depth %.1f mm (max %.1f), rotation deviation mean %.2f "
        "deg "
        "(p99 %.2f), stance-foot drift p99 %.1f mm (max %.1f), foot pops %d (worst excess %.1f cm), max "
        "joint "
        "speed %.1f m/s, CG %.1f, rejected %d\n",
        scenario.c_str(), n, 100 * qr.overlap_reduction, 1000 * qr.quality.depth_p99_m,
        1000 * qr.quality.depth_max_m, qr.quality.rotation_dev_mean_deg, qr.quality.rotation_dev_p99_deg,
        1000 * qr.quality.feet.stance_drift_p99_m, 1000 * qr.quality.feet.stance_drift_max_m,
        qr.quality.feet.foot_pops, 100 * qr.quality.feet.pop_excess_max_m, qr.quality.joint_speed_max_mps,
        report.cg_iterations_mean, report.rejected_steps);
    std::printf(
        "%-10s %3d characters: free-limb deviation p99 %.2f deg (max %.2f), joint flips %ld, environment "
        "penetration p99 %.1f mm (max %.1f), floating p99 %.1f mm, feet below ground max %.1f mm (added by "
        "the correction %.1f)\n",
        scenario.c_str(), n, qr.quality.free_limbs.p99_deg, qr.quality.free_limbs.max_deg,
        qr.quality.flips.count, 1000 * qr.quality.environment.p99_m, 1000 * qr.quality.environment.max_m,
        1000 * qr.quality.feet.float_p99_m, 1000 * qr.quality.feet.ground_penetration_max_m,
        1000 * qr.quality.feet.ground_penetration_added_max_m);
    if (qr.quality.mesh_overlap.frames > 0)
      std::printf(
          "%-10s %3d characters: rendered vertices inside another character %.4f %% (baseline %.4f %%), "
          "depth "
          "p99 %.1f mm; within 5 mm of their capsules %.2f %% (outside p99 %.1f mm)\n",
          scenario.c_str(), n, 100 * qr.quality.mesh_overlap.fraction_mean,
          100 * qr.baseline_mesh.fraction_mean, 1000 * qr.quality.mesh_overlap.depth_p99_m,
          100 * qr.quality.proxy_coverage.within_share, 1000 * qr.quality.proxy_coverage.outside_p99_m);
    quality.push_back(qr);
  }
}

void run(const Options& o) {
  std::vector<OverlapRow> rows;
  std::vector<QualityRow> quality;
  run_scenario(o.stationary, o, rows, quality);
  run_scenario(o.corridor, o, rows, quality);
  write_overlap_vs_density(rows, o.out);
  std::string qcsv = csv_line({"scenario",
                               "characters",
                               "density",
                               "overlap_reduction",
                               "depth_p99_m",
                               "depth_max_m",
                               "rotation_dev_mean_deg",
                               "rotation_dev_p99_deg",
                               "foot_skate_max_m",
                               "joint_speed_max_mps",
                               "cg_iterations_mean",
                               "rejected_steps",
                               "stance_foot_drift_p99_m",
                               "stance_foot_drift_max_m",
                               "foot_pops",
                               "foot_pop_excess_max_m",
                               "foot_ground_penetration_max_m",
                               "foot_ground_penetration_added_max_m",
                               "foot_float_p99_m",
                               "free_limb_dev_p99_deg",
                               "free_limb_dev_max_deg",
                               "joint_flips",
                               "env_penetration_p99_m",
                               "env_penetration_max_m",
                               "mesh_overlap_fraction",
                               "baseline_mesh_overlap_fraction",
                               "mesh_overlap_depth_p99_m",
                               "proxy_coverage",
                               "proxy_outside_p99_m"});
  for (const QualityRow& r : quality) {
    const bool meshes = r.quality.mesh_overlap.frames > 0;
    auto mesh_cell = [&](double v) { return meshes ? csv_number(v) : std::string(); };
    qcsv += csv_line({r.scenario,
                      std::to_string(r.characters),
                      csv_number(r.density),
                      csv_number(r.overlap_reduction),
                      csv_number(r.quality.depth_p99_m),
                      csv_number(r.quality.depth_max_m),
                      csv_number(r.quality.rotation_dev_mean_deg),
                      csv_number(r.quality.rotation_dev_p99_deg),
                      csv_number(r.quality.foot_skate_max_m),
                      csv_number(r.quality.joint_speed_max_mps),
                      csv_number(r.report.cg_iterations_mean),
                      std::to_string(r.report.rejected_steps),
                      csv_number(r.quality.feet.stance_drift_p99_m),
                      csv_number(r.quality.feet.stance_drift_max_m),
                      std::to_string(r.quality.feet.foot_pops),
                      csv_number(r.quality.feet.pop_excess_max_m),
                      csv_number(r.quality.feet.ground_penetration_max_m),
                      csv_number(r.quality.feet.ground_penetration_added_max_m),
                      csv_number(r.quality.feet.float_p99_m),
                      csv_number(r.quality.free_limbs.p99_deg),
                      csv_number(r.quality.free_limbs.max_deg),
                      std::to_string(r.quality.flips.count),
                      csv_number(r.quality.environment.p99_m),
                      csv_number(r.quality.environment.max_m),
                      mesh_cell(r.quality.mesh_overlap.fraction_mean),
                      mesh_cell(r.baseline_mesh.fraction_mean),
                      mesh_cell(r.quality.mesh_overlap.depth_p99_m),
                      mesh_cell(r.quality.proxy_coverage.within_share),
                      mesh_cell(r.quality.proxy_coverage.outside_p99_m)});
  }
  write_file_atomic(fs::path(o.out) / "correction_quality.csv", qcsv);
  std::printf(
      "wrote %s/overlap_vs_density.csv, correction_quality.csv and "
      "overlap_vs_density_{stationary,corridor}.png|svg\n",
      o.out.c_str());
}

}  // namespace

void add_experiment_overlap_command(Command& root) {
  auto o = std::make_shared<Options>();
  auto* cmd = experiment_group(root)->add_subcommand(
      "overlap-vs-density",
      "Seed 000 Figure 3: per-character overlap volume vs density, baseline and corrected");
  cmd->add_option("--out", o->out, "Output folder")->capture_default_str();
  cmd->add_option("--stationary", o->stationary, "Stationary (concert) spec")
      ->check(check::existing_file())
      ->capture_default_str();
  cmd->add_option("--corridor", o->corridor, "Corridor (non-stationary) spec")
      ->check(check::existing_file())
      ->capture_default_str();
  cmd->add_option("--duration", o->duration_s, "Seconds of animation per density")
      ->check(check::range(0.2, 60.0))
      ->capture_default_str();
  cmd->add_option("--fps", o->fps, "Frames per second")
      ->check(check::range(5.0, 120.0))
      ->capture_default_str();
  add_corrector_tuning_options(cmd, o->params);
  cmd->add_option("--contact-offset", o->params.contact_offset_m,
                  "Inter-body contact offset (m): the penalty acts on depth + offset")
      ->check(check::range(0.0, 0.1))
      ->capture_default_str();
  cmd->add_flag("--inertial-prediction", o->inertial_prediction,
                "Detect contacts at the inertial prediction instead of the exact contact-free step");
  cmd->add_option("--foot-anchor-stiffness", o->params.foot_anchor_stiffness,
                  "World-position spring on planted ankles and feet (1/s^2 per kg, x stiff_joint_gain)")
      ->capture_default_str();
  cmd->add_option("--swing-foot-stiffness", o->params.swing_foot_stiffness,
                  "World-position spring pulling swinging ankles and feet to their targets (1/s^2 per kg, x "
                  "stiff_joint_gain)")
      ->capture_default_str();
  cmd->add_option("--foot-hold-tolerance", o->params.foot_hold_tolerance_m,
                  "How far (m) a planted foot may be pushed before leg IK puts it back")
      ->check(check::range(0.0, 0.1))
      ->capture_default_str();
  cmd->add_option("--max-rotation-step", o->params.max_rotation_step_rad,
                  "Trust region on each bone's contact rotation per step (rad, 0 = off)")
      ->capture_default_str();
  cmd->add_option("--settle-steps", o->params.settle_steps, "Steps run on frame 0 before the output starts")
      ->capture_default_str();
  add_proxy_fit_options(cmd, o->proxies, "both methods are measured with them");
  cmd->add_flag("--save-crowds", o->save_crowds,
                "Also write each density's baseline and corrected crowd files, "
                "OUT/crowds/SCENARIO_density-D/{baseline,ours}.glb, for `crowdlab metrics`, `render` and "
                "`correct`");
  cmd->callback([o] {
    const OutputFolderLock lock(o->out);  // one process per folder (output_folder_lock.hpp)
    run(*o);
  });
}

}  // namespace crowdlab::cli::cmd_experiment_overlap
