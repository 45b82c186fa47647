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

namespace crowdlab::cli::cmd_correct {
namespace {

struct CorrectOptions {
  std::string in_path, out_path;
  CorrectorParams params;
  std::optional<ProxyFit> proxies;  ///< empty: the capsules the crowd file carries
};

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
  add_proxy_fit_options(cmd, opt->proxies, "the output carries them");
  cmd->callback([opt] {
    CrowdAnimation in = read_crowd_glb(opt->in_path);
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
