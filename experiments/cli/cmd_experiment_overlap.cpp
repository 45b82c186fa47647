// `crowdlab experiment overlap-vs-density --out DIR`: seed 000 Figure 3. For the stationary concert
// (20..60 characters on 9 m^2) and the corridor, the per-character mean overlap volume of the baseline
// animation and of the corrected one, at every density of the shipped specs.
// Writes DIR/overlap_vs_density.csv (scenario,characters,density,method,mean_overlap_l) and
// DIR/overlap_vs_density.png|svg.
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>

#include "experiments/cli/command_registry.hpp"
#include "experiments/cli/experiment_group.hpp"
#include "experiments/cli/figures/overlap_vs_density.hpp"
#include "experiments/cli/pipeline/body_model.hpp"
#include "framework/animation/animate_crowd.hpp"
#include "framework/core/progress.hpp"
#include "framework/core/seed.hpp"
#include "framework/correction/correct_crowd.hpp"
#include "framework/crowd/generate_scenario.hpp"
#include "framework/metrics/measure_crowd.hpp"
#include "framework/spec/load_experiment_spec.hpp"

namespace crowdlab::cli {
namespace {
namespace fs = std::filesystem;

struct Options {
  std::string out = "overlap-vs-density";
  std::string stationary = "experiments/gomez2024_stationary.yaml";
  std::string corridor = "experiments/gomez2024_nonstationary.yaml";
  double duration_s = 4.0;  ///< seconds of animation per density (the paper's clips are 20 s)
  double fps = 30.0;
};

void run_scenario(const std::string& spec_path, const Options& o, std::vector<OverlapRow>& rows) {
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
    AnimationContext ctx;
    ctx.scenario_type = s.scenario;
    ctx.seed = crowd_condition.seed;
    ctx.condition_id = "density-" + density;
    apply_body_model(spec.animation, s.trajectories.agents.size(), ctx);
    const CrowdAnimation baseline = animate_crowd(s.trajectories, s.environment, spec.animation, ctx);
    CorrectorParams params;
    params.damping = spec.correction.damping;
    Progress progress(s.scenario + " density " + density + ": correcting",
                      static_cast<size_t>(baseline.frame_count()));
    const CrowdAnimation ours = correct_crowd(baseline, params, &progress);
    progress.finish();
    const int n = static_cast<int>(baseline.characters.size());
    rows.push_back({s.scenario, n, c.number("density", 0), "baseline",
                    measure_crowd(baseline).mean_character_overlap_l});
    rows.push_back(
        {s.scenario, n, c.number("density", 0), "ours", measure_crowd(ours).mean_character_overlap_l});
    std::printf("%-10s %3d characters (%.2f/m2): baseline %.3f L, ours %.3f L per character\n",
                s.scenario.c_str(), n, c.number("density", 0), rows[rows.size() - 2].mean_overlap_l,
                rows.back().mean_overlap_l);
  }
}

void run(const Options& o) {
  std::vector<OverlapRow> rows;
  run_scenario(o.stationary, o, rows);
  run_scenario(o.corridor, o, rows);
  write_overlap_vs_density(rows, o.out);
  std::printf("wrote %s/overlap_vs_density.csv and overlap_vs_density_{stationary,corridor}.png|svg\n",
              o.out.c_str());
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* cmd = experiment_group(root)->add_subcommand(
      "overlap-vs-density",
      "Seed 000 Figure 3: per-character overlap volume vs density, baseline and corrected");
  cmd->add_option("--out", o->out, "Output folder")->capture_default_str();
  cmd->add_option("--stationary", o->stationary, "Stationary (concert) spec")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  cmd->add_option("--corridor", o->corridor, "Corridor (non-stationary) spec")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  cmd->add_option("--duration", o->duration_s, "Seconds of animation per density")
      ->check(CLI::Range(0.2, 60.0))
      ->capture_default_str();
  cmd->add_option("--fps", o->fps, "Frames per second")->check(CLI::Range(5.0, 120.0))->capture_default_str();
  cmd->callback([o] { run(*o); });
});

}  // namespace
}  // namespace crowdlab::cli
