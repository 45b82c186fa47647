// `crowdlab correct IN.glb --out OUT.glb`: the physics-based collision correction of seed 000 §3
// ("Ours"), frame by frame over a crowd file, written as a new crowd file.
#include <spdlog/spdlog.h>

#include <memory>
#include <optional>
#include <string>

#include "experiments/cli/command_table.hpp"
#include "experiments/cli/corrector_tuning_options.hpp"
#include "experiments/cli/proxy_fit_options.hpp"
#include "framework/core/progress.hpp"
#include "framework/correction/correct_crowd.hpp"
#include "framework/correction/environment_point_tree.hpp"
#include "framework/io/read_crowd_glb.hpp"
#include "framework/io/write_crowd_glb.hpp"
#include "framework/pipeline/crowd_recipes.hpp"
#include "framework/spec/condition_kinds.hpp"

namespace crowdlab::cli::cmd_correct {
namespace {

struct CorrectOptions {
  std::string in_path, out_path;
  CorrectorParams params;
  std::optional<ProxyFit> proxies;  ///< empty: the capsules the crowd file carries
  double follow_root_s = 0.0;
  bool follow_root_given = false;  ///< false: as `run` corrects the crowd file's scenario
};

/// `params` with what `run` sets for the crowd file's scenario (meta.scenario; nothing for a name it does
/// not know), its root following as given when it is.
void as_run_corrects(const CrowdAnimation& crowd, const CorrectOptions& opt, CorrectorParams& params) {
  const std::optional<ScenarioKind> scenario = parse_kind<ScenarioKind>(crowd.meta.scenario);
  if (scenario && walks_on_flat_ground(*scenario)) walking_correction(params);
  if (opt.follow_root_given) params.follow_root_smoothing_s = opt.follow_root_s;
}

}  // namespace

void add_correct_command(Command& root) {
  auto opt = std::make_shared<CorrectOptions>();
  auto* cmd = root.add_subcommand(
      "correct",
      "Resolve the collisions between the characters of a crowd file (.glb) with the physics-based "
      "correction of Gomez-Nogales et al. 2024 (seed 000 §3) and write the corrected crowd (.glb)");
  cmd->add_option("crowd", opt->in_path, "Crowd file to correct (.glb)")->required();
  cmd->add_option("-o,--out", opt->out_path, "Corrected crowd file to write (.glb)")->required();
  cmd->add_option("--stiffness", opt->params.stiffness,
                  "Control spring k of Eq. 4, per unit joint inertia (1/s^2); lower = bodies give way more")
      ->capture_default_str();
  cmd->add_option("--damping", opt->params.damping,
                  "Control damping d of Eq. 4 on the deviation velocity (paper: 0.006)")
      ->capture_default_str();
  add_corrector_tuning_options(cmd, opt->params);
  cmd->add_option("--max-environment-points", opt->params.max_environment_points,
                  "Refuse an environment that samples into more points than this (about 40 bytes each)")
      ->check(check::positive_number())
      ->capture_default_str();
  cmd->add_option(
         "--follow-root", opt->follow_root_s,
         "Correct twice, the second time toward the input moved onto the first correction's roots "
         "(their horizontal offsets smoothed over this Gaussian sigma, s) with its footprints moved "
         "alike; 0 = one correction. Default: as `run`, 0.3 for crowds walking on the flat ground "
         "(the crowd file's scenario: corridor, flows, crossing pairs), which also get --settle-feet "
         "and --feet-above-ground; else 0 (docs/correction.md)")
      ->check(check::range(0.0, 10.0))
      ->each([opt](const std::string&) { opt->follow_root_given = true; });
  add_proxy_fit_options(cmd, opt->proxies, "the output carries them");
  cmd->callback([opt] {
    CrowdAnimation in = read_crowd_glb(opt->in_path);
    as_run_corrects(in, *opt, opt->params);
    fit_crowd_proxies(in, opt->proxies.value_or(ProxyFit::volume));
    check_environment_sampling(in.environment, opt->params.environment_sample_spacing_m,
                               opt->params.max_environment_points, opt->in_path);
    Progress progress("correcting " + opt->in_path, correction_steps(in, opt->params));
    CorrectionReport report;
    const CrowdAnimation out = correct_crowd(in, opt->params, &progress, &report);
    progress.finish();
    write_crowd_glb(out, opt->out_path);
    spdlog::info(
        "corrected {} characters x {} frames: {:.1f} contacts and {:.1f} CG iterations per step, "
        "{} rejected steps; wrote {}",
        in.characters.size(), report.frames, report.contacts_mean, report.cg_iterations_mean,
        report.rejected_steps, opt->out_path);
  });
}

}  // namespace crowdlab::cli::cmd_correct
