// `crowdlab correct IN.glb --out OUT.glb`: the physics-based collision correction of seed 000 §3
// ("Ours"), frame by frame over a crowd file, written as a new crowd file.
#include <spdlog/spdlog.h>

#include <memory>
#include <string>

#include "experiments/cli/command_table.hpp"
#include "experiments/cli/corrector_tuning_options.hpp"
#include "framework/body/cover_capsules.hpp"
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
  bool cover_mesh = false;
  bool fit_proxies = false;
};

/// Fits every meshed character's capsules to its rendered mesh (body/cover_capsules.hpp) and logs the share
/// of rest-pose vertices within 5 mm of them before and after (and of the bounded ones within their
/// surface's tolerance).
void cover_meshes(CrowdAnimation& crowd, const SurfaceTolerances& tolerances, bool move_axes) {
  double before = 0, after = 0, bounded = 0;
  int n = 0;
  for (CharacterAnimation& c : crowd.characters) {
    if (!c.mesh) continue;
    const CoverReport r = fit_capsules_to_mesh(c.shape, *c.mesh, tolerances, move_axes);
    before += r.within_before;
    after += r.within_after;
    bounded += r.bounded_within_after;
    ++n;
  }
  if (n > 0)
    spdlog::info(
        "capsules fitted to the rendered meshes of {} characters: {:.2f} % -> {:.2f} % of rest-pose "
        "vertices within 5 mm, {:.2f} % of the bounded ones within their surface's tolerance (means over "
        "characters)",
        n, 100 * before / n, 100 * after / n, 100 * bounded / n);
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
  auto* cover = cmd->add_flag(
      "--cover-mesh", opt->cover_mesh,
      "Grow each character's capsules until its rendered mesh (MPFB2 skin, garments, hair) lies "
      "within 5 mm of them in the rest pose, before correcting; the output carries the grown capsules");
  cmd->add_flag("--fit-proxies", opt->fit_proxies,
                "Fit each character's capsules to its rendered mesh per surface before correcting: skin, "
                "face, garments and shoe uppers within 5 mm, hair within 20 mm, soles not bounded, each "
                "capsule's axis moved toward the surface it must take in (docs/correction.md); the output "
                "carries the fitted capsules")
      ->excludes(cover);
  cmd->callback([opt] {
    CrowdAnimation in = read_crowd_glb(opt->in_path);
    if (opt->cover_mesh) cover_meshes(in, SurfaceTolerances::uniform(0.005), false);
    if (opt->fit_proxies) cover_meshes(in, SurfaceTolerances::per_surface(), true);
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
